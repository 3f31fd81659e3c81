#!/usr/bin/env bash
# Runs every test: installs missing Debian packages, builds into build/, runs ctest.
# Exits non-zero on any failure. Extra arguments go to ctest (e.g. -L unit, -R lpv).
#
# --sanitize: the same suite built with AddressSanitizer and UBSan (CAVELIGHT_SANITIZE)
# into build-sanitize/, every report fatal, then every fuzz target once over its seeds and
# the corpus that the normal run's fuzzing grew in build/. Green means 0 reports. Leaks
# are checked in every test program; the integration scripts' processes (shells, Python,
# nodes that load the GL driver) are checked for memory errors and UB, not for leaks.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
. "$root/scripts/deps.sh"
cavelight_install_deps
if [ "${1:-}" != --sanitize ]; then
  cavelight_build "$root"
  cd "$root/build"
  ctest --output-on-failure -j "$(nproc)" "$@"
  exit 0
fi
shift
cavelight_build "$root" build-sanitize -DCAVELIGHT_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo
# Leaks inside the GL driver, GLFW and the X libraries are theirs, not ours (tests/sanitize/).
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS=suppressions=$root/tests/sanitize/lsan.supp:print_suppressions=0
cd "$root/build-sanitize"
ctest --output-on-failure -j "$(nproc)" -LE 'fuzz|integration' "$@"
ASAN_OPTIONS=$ASAN_OPTIONS:detect_leaks=0 ctest --output-on-failure -j "$(nproc)" -L integration "$@"
for fuzz in fuzz_*; do
  [ -x "$fuzz" ] && [ -f "$fuzz" ] || continue
  name=${fuzz#fuzz_}
  # A fuzz target has its seeds in the tree (fuzz_probe, CMake's libFuzzer check, has none).
  [ -d "$root/tests/fuzz/$name" ] || continue
  corpora=("$root/tests/fuzz/$name")
  [ -d "$root/build/fuzz_${name}_corpus" ] && corpora+=("$root/build/fuzz_${name}_corpus")
  echo "sanitize: $fuzz over ${corpora[*]}"
  "./$fuzz" -runs=0 -rss_limit_mb=2048 "${corpora[@]}" > "$fuzz.log" 2>&1 || { tail -40 "$fuzz.log"; exit 1; }
done
echo "sanitize: suite and fuzz corpora clean"

#!/usr/bin/env bash
# A render node on a GPU host needs neither Mesa's software stack nor Embree: OSMesa (and
# the LLVM it pulls in) and Embree are loaded when asked for (common/base/dynlib.h), so no program
# links them; asked for and missing, each is refused in one line naming the library and the
# Debian package, exit 1. Where user namespaces are allowed the libraries are hidden by
# binding an empty file over them; the GL context and the reference still work when they
# are there.
set -euo pipefail
build=$(cd "${1:?usage: $0 BUILD_DIR}" && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

for prog in cavelight-node cavelight-master cavelight-bench; do
  ldd "$build/$prog" > "$out/ldd" || fail "ldd $prog"
  ! grep -E "libOSMesa|libLLVM|libembree|libtbb" "$out/ldd" || fail "$prog links a library it should load on demand"
done
echo "no program links OSMesa, LLVM or Embree"

node=$build/cavelight-node
"$node" --standalone --gl osmesa --width 32 --height 24 --out "$out/osmesa" 2> "$out/err" \
  && [ -s "$out/osmesa/frame0000_mono.png" ] || fail "OSMesa render: $(cat "$out/err")"
"$node" --standalone --renderer reference --samples 1 --width 32 --height 24 --out "$out/ref" 2> "$out/err" \
  || fail "reference render: $(cat "$out/err")"
echo "loaded when asked for: an OSMesa context and the Embree reference render"

osmesa=$(ldconfig -p | awk '/libOSMesa\.so\.8 .*x86-64|libOSMesa\.so\.8 / && !found {print $NF; found = 1}')
embree=$(ldconfig -p | awk '/libembree3\.so\.3 / && !found {print $NF; found = 1}')
if [ -z "$osmesa" ] || [ -z "$embree" ] || ! unshare -rm true 2> /dev/null; then
  echo "user namespaces or the libraries' paths not available here: the missing-library lines are not tried"
  exit 0
fi
hide="mount --bind /dev/null $(readlink -f "$osmesa") && mount --bind /dev/null $(readlink -f "$embree")"
one_line() { # expected command...
  local want=$1 rc=0; shift
  unshare -rm sh -c "$hide && exec \"\$@\"" sh "$@" > /dev/null 2> "$out/err" || rc=$?
  [ $rc = 1 ] || fail "$* exited $rc without its library: $(cat "$out/err")"
  [ "$(wc -l < "$out/err")" = 1 ] && grep -q "$want" "$out/err" || fail "$*: $(cat "$out/err")"
}
one_line "OSMesa: cannot load libOSMesa.so.8 (.*); install libosmesa6" "$node" --standalone --gl osmesa --width 32 --height 24
one_line "Embree: cannot load libembree3.so.3 (.*); install libembree3-3" \
  "$node" --standalone --renderer reference --samples 1 --width 32 --height 24
for gi in ilpv vpl; do
  unshare -rm sh -c "$hide && exec \"\$@\"" sh "$node" --standalone --gi $gi --width 32 --height 24 --out "$out/egl" \
    2> "$out/err" || fail "an EGL node on $gi failed without OSMesa and Embree: $(cat "$out/err")"
done
one_line "Embree: cannot load libembree3.so.3" "$node" --standalone --gi vpl --vpl-selection view --width 32 --height 24
echo "missing OSMesa or Embree: one line naming the package; an EGL node on ilpv or vpl does not need them"

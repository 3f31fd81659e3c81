#!/usr/bin/env bash
# scripts/bundle.sh packs the node and the master with their runtime libraries: in the
# bundle every library but the host's own (glibc, the GL vendor libraries) resolves inside
# it; the bundled node renders standalone and loads the bundle's Embree; and where user
# namespaces are allowed, with the host's copies of the packed libraries hidden (an empty
# file bound over each), the bundled node still renders while the build's node cannot start.
set -euo pipefail
build=$(cd "${1:?usage: $0 BUILD_DIR}" && pwd)
root=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
b=$tmp/bundle

bash "$root/scripts/bundle.sh" "$b" "$build" > "$tmp/bundle.log" || { cat "$tmp/bundle.log"; fail "bundle.sh"; }
cat "$tmp/bundle.log"
for prog in cavelight-node cavelight-master; do
  ldd "$b/bin/$prog" | awk '$2 == "=>" {print $1, $3}' | while read -r soname path; do
    case $soname in
      libc.so*|libm.so*|libdl.so*|libpthread.so*|librt.so*|libresolv.so*|libEGL.so*|libGL*.so*) ;;
      *) [[ $(readlink -f "$path") == "$b/lib/"* ]] || fail "$prog: $soname resolves to $path, outside the bundle" ;;
    esac
  done
done
[ -f "$b/share/cavelight/shaders/common.glsl" ] || fail "no shaders in the bundle"
echo "every library but the host's resolves inside the bundle"

cd "$tmp"
LD_DEBUG=files "$b/bin/cavelight-node" --standalone --renderer reference --samples 1 --width 32 --height 24 \
  > /dev/null 2> "$tmp/ref.log" || { tail -5 "$tmp/ref.log"; fail "bundled reference"; }
grep -q "calling init: $b/bin/../lib/libembree3.so.3" "$tmp/ref.log" &&
  grep -q "calling init: $b/bin/../lib/libtbb.so.12" "$tmp/ref.log" \
  || fail "Embree or its TBB were not loaded from the bundle"
"$b/bin/cavelight-node" --standalone --width 64 --height 48 --out "$tmp/one" 2> "$tmp/node.log" \
  && [ -s "$tmp/one/frame0000_mono.png" ] || { cat "$tmp/node.log"; fail "the bundled node did not render"; }
echo "the bundled node renders standalone, Embree and TBB from the bundle"

if ! unshare -rm true 2> /dev/null; then
  echo "user namespaces not available here: the host's libraries are not hidden"
  exit 0
fi
hide=""
# awk reads ldconfig's list to the end: leaving early would kill ldconfig with SIGPIPE,
# which pipefail turns into a failed assignment that ends the script.
for f in "$b"/lib/*; do
  sys=$(ldconfig -p | awk -v n="$(basename "$f")" '$1 == n && $NF ~ /^\// && !found {print $NF; found = 1}')
  [ -n "$sys" ] && hide+="mount --bind /dev/null $(readlink -f "$sys") && "
done
unshare -rm sh -c "${hide}exec \"\$@\"" sh "$b/bin/cavelight-node" --standalone --width 64 --height 48 \
  --out "$tmp/hidden" 2> "$tmp/hidden.log" && [ -s "$tmp/hidden/frame0000_mono.png" ] \
  || { cat "$tmp/hidden.log"; fail "the bundled node needs the host's copies of packed libraries"; }
if unshare -rm sh -c "${hide}exec \"\$@\"" sh "$build/cavelight-node" --standalone --width 64 --height 48 \
  > /dev/null 2>&1; then
  fail "the build's node ran with the libraries hidden: the hiding proves nothing"
fi
echo "with the host's copies of $(ls "$b/lib" | wc -l) packed libraries hidden, the bundled node renders"

#!/usr/bin/env bash
# Packs the render node and the master with their runtime libraries into one folder that
# runs on a host without package access (a lent GPU machine, a render PC with no network):
#   OUT/bin/cavelight-node, cavelight-master    (they look in ../lib first: RPATH)
#   OUT/lib/                                    every library they need beyond the host's
#   OUT/share/cavelight/                        shaders, example configs and scenes
# Copy OUT anywhere and run OUT/bin/cavelight-node; the master starts the node beside it.
#
# Left out, because they must come from the host:
#   glibc (libc, libm, libdl, libpthread, librt, libresolv, the loader ld-linux): the
#     programs run under the host's loader, which only works with its own C library (so
#     the host's glibc must be at least as new as this machine's: `ldd --version`);
#   the GL vendor libraries (glvnd: libEGL, libGL, libGLX, libOpenGL, libGLdispatch, libGLES):
#     the host's GPU driver installs them and registers its GPU there (NVIDIA's, Mesa's);
#     a copy from this machine would not know that driver;
#   OSMesa (software GL, with LLVM): loaded only for --gl osmesa, which a GPU host does not
#     use. Embree (the reference, the vpl view rule) is loaded on demand too, and is packed.
# Usage: scripts/bundle.sh OUT [BUILD_DIR]   (default: the build/ folder of this checkout)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:?usage: scripts/bundle.sh OUT [BUILD_DIR]}
build=$(cd "${2:-$root/build}" && pwd)
host_libs='^(ld-linux.*|libc|libm|libdl|libpthread|librt|libresolv|libutil|libanl|libnsl|libEGL|libGL|libGLX|libOpenGL|libGLdispatch|libGLES.*)\.so'

for c in node master; do
  cmake --install "$build" --prefix "$out" --component "$c" > /dev/null
done
mkdir -p "$out/lib"
# Embree is dlopen()ed: pack it and what it needs like a linked library.
embree=$(ldconfig -p | awk '$1 == "libembree3.so.3" && !found {print $NF; found = 1}')
[ -n "$embree" ] || { echo "bundle: libembree3.so.3 not found (install libembree3-3)" >&2; exit 1; }
cp -L "$embree" "$out/lib/libembree3.so.3"
for f in "$out/bin/cavelight-node" "$out/bin/cavelight-master" "$embree"; do
  ldd "$f" | awk '$2 == "=>" && $3 ~ /^\// {print $1, $3}'
done | sort -u | while read -r soname path; do
  [[ $soname =~ $host_libs ]] && continue
  cp -L "$path" "$out/lib/$soname"
done
echo "bundle: $out: cavelight-node, cavelight-master and $(ls "$out/lib" | wc -l) libraries ($(du -sh "$out" | cut -f1))"

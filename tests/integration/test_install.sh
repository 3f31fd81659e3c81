#!/usr/bin/env bash
# `cmake --install` into a scratch prefix: the programs, their shaders, the example configs
# and scenes, the licence, libcavelight with its header and pkg-config file; the installed
# node renders from there and reads the installed shaders (a broken installed shader
# breaks it, naming the installed file), the installed master starts the installed node
# beside it, and an application built against the installed library alone (pkg-config)
# runs in both.
set -euo pipefail
build=$(cd "${1:?usage: $0 BUILD_DIR}" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
prefix=$tmp/prefix

cmake --install "$build" --prefix "$prefix" > "$tmp/install.log" || { cat "$tmp/install.log"; fail "cmake --install"; }
for f in bin/cavelight-node bin/cavelight-master bin/cavelight-compare bin/cavelight-bench \
         share/cavelight/shaders/common.glsl share/cavelight/shaders/shade.frag \
         share/cavelight/configs/clusters/desktop-local.json share/cavelight/scenes/room.gltf \
         share/doc/cavelight/LICENSE include/cavelight/app.h lib/libcavelight.so lib/pkgconfig/cavelight.pc; do
  [ -e "$prefix/$f" ] || fail "$f was not installed"
done
echo "installed: $(find "$prefix" -type f | wc -l) files"

cd "$tmp"
"$prefix/bin/cavelight-node" --standalone --scene "$prefix/share/cavelight/scenes/room.gltf" --width 64 --height 48 \
  --out "$tmp/one" 2> "$tmp/node.log" && [ -s "$tmp/one/frame0000_mono.png" ] || { cat "$tmp/node.log"; fail "installed node"; }
shader=$prefix/share/cavelight/shaders/common.glsl
cp "$shader" "$tmp/common.glsl"
echo "this is no GLSL" >> "$shader"
if "$prefix/bin/cavelight-node" --standalone --width 64 --height 48 --out "$tmp/broken" 2> "$tmp/broken.log"; then
  fail "the installed node did not read the installed shaders (it rendered with a broken one)"
fi
cp "$tmp/common.glsl" "$shader"
echo "the installed node renders with the installed shaders"

config=$tmp/desktop.json
cp "$prefix/share/cavelight/configs/clusters/desktop-local.json" "$config"
"$prefix/bin/cavelight-master" --config "$config" --bind 'tcp://127.0.0.1:*' --spawn-local --frames 2 \
  --output png --out "$tmp/cluster" --quiet 2> "$tmp/master.log" || { cat "$tmp/master.log"; fail "installed master"; }
ls "$tmp"/cluster/*.png > /dev/null 2>&1 || { cat "$tmp/master.log"; fail "the installed master's node wrote no image"; }
echo "the installed master starts the installed node: $(ls "$tmp"/cluster/*.png | wc -l) images"

# An application from an empty folder: the example's source, the installed SDK only.
cp "$(cd "$(dirname "$0")/../.." && pwd)/examples/move.c" "$tmp/mine.c"
flags=$(PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config --cflags --libs cavelight)
cc -shared -fPIC -o "$tmp/mine.so" "$tmp/mine.c" $flags -lm 2> "$tmp/cc.log" || { cat "$tmp/cc.log"; fail "an application against the installed SDK"; }
"$prefix/bin/cavelight-master" --config "$config" --bind 'tcp://127.0.0.1:*' --spawn-local --frames 3 \
  --app "$tmp/mine.so" --output headless --out "$tmp/app" --report "$tmp/app.json" 2> "$tmp/app.log" \
  || { cat "$tmp/app.log"; fail "the installed master with an application"; }
grep -q "app move loaded" "$tmp/app.log" || { cat "$tmp/app.log"; fail "the application was not loaded"; }
[ "$(python3 -c 'import json, sys; r = json.load(open(sys.argv[1])); print(r["frames"], r["desyncs"])' "$tmp/app.json")" = "3 0" ] \
  || fail "the application's session did not run 3 frames with equal checksums"
echo "an application built with pkg-config cavelight runs in the installed master and node"

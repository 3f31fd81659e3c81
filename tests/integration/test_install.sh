#!/usr/bin/env bash
# `cmake --install` into a scratch prefix: the programs, their shaders, the example configs
# and scenes, the licence; the installed node renders from there and reads the installed
# shaders (a broken installed shader breaks it, naming the installed file), and the
# installed master starts the installed node beside it.
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
         share/doc/cavelight/LICENSE; do
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

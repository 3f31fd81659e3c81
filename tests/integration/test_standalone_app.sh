#!/usr/bin/env bash
# An application without a cluster: cavelight-node --standalone --app runs its init,
# update, frame and draw in one process. examples/points.so draws a spiral whose angle key
# its update sets and its frame reads: the picture differs from the room's without it,
# and from frame 0 to frame 1 only where the spiral turned. A file that is no application
# is refused in one line naming it.
set -euo pipefail
build=$1
node="$build/cavelight-node"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
args=(--standalone --frames 2 --width 96 --height 72 --rsm 64 --lattice 16 --lambda 0 --exposure 1)

"$node" "${args[@]}" --out "$out/room" > /dev/null 2> "$out/room.err" || { cat "$out/room.err" >&2; fail "room"; }
"$node" "${args[@]}" --app "$build/examples/points.so" --out "$out/app" > /dev/null 2> "$out/app.err" \
    || { cat "$out/app.err" >&2; fail "--standalone --app exited non-zero"; }
grep -q "app points loaded" "$out/app.err" || { cat "$out/app.err" >&2; fail "no line that the app loaded"; }
cmp -s "$out/room/frame0000_mono.png" "$out/app/frame0000_mono.png" && fail "the app drew nothing"
# lambda 0: every frame's light is the same, so the room alone renders frame 1 as frame 0;
# with the app, the spiral turned by its key.
cmp -s "$out/room/frame0000_mono.png" "$out/room/frame0001_mono.png" || fail "the room alone changed between frames"
cmp -s "$out/app/frame0000_mono.png" "$out/app/frame0001_mono.png" && fail "the app's key did not turn the spiral"

if "$node" "${args[@]}" --app "$build/cavelight-node" > /dev/null 2> "$out/bad.err"; then
    fail "a file that is no application was taken"
fi
[ "$(wc -l < "$out/bad.err")" -eq 1 ] && grep -q "app .*cavelight-node" "$out/bad.err" \
    || { cat "$out/bad.err" >&2; fail "not one line naming the file"; }
echo "ok: --standalone --app draws and updates; a non-application refused in one line"

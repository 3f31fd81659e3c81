#!/usr/bin/env bash
# Window output on a virtual X display (Xvfb): a stereo node with two screens runs every
# stereo mode (side-by-side, top-bottom, anaglyph, quad-buffered with its fallback, one
# window per eye) through a few frames of the barrier and leaves cleanly; a node started
# without DISPLAY (over ssh, as a service) opens its window on the config's "display".
# Skipped where Xvfb is missing.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/cluster_lib.sh"
if ! command -v xvfb-run >/dev/null; then echo "SKIP: xvfb-run not installed"; exit 77; fi

make_config "$tmp/base.json" 20000 d
for mode in side-by-side top-bottom anaglyph quad window-per-eye; do
  python3 - "$tmp/base.json" "$tmp/$mode.json" "$mode" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c["nodes"][0].update({"screens": ["front-l", "front-r"], "output": "window", "stereo": sys.argv[3]})
json.dump(c, open(sys.argv[2], "w"))
PY
  xvfb-run -a -n $((100 + RANDOM % 800)) -s "-screen 0 640x480x24" "$build/cavelight-master" --config "$tmp/$mode.json" \
    --bind 'tcp://127.0.0.1:*' --spawn-local --frames 4 --report "$tmp/$mode-r.json" \
    --node-args "$small_render" 2> "$tmp/$mode.log" || { cat "$tmp/$mode.log"; fail "$mode: cluster failed"; }
  [ "$(json 'r["per_node"][0]["frames_ready"]' "$tmp/$mode-r.json")" = 4 ] || { cat "$tmp/$mode.log"; fail "$mode: not 4 frames"; }
  ! grep -q "node d \(exited\|was killed\)" "$tmp/$mode.log" || { cat "$tmp/$mode.log"; fail "$mode: node crashed"; }
  note=""; grep -q "no quad-buffered window" "$tmp/$mode.log" && note=" (no quad buffers on this driver: side-by-side)"
  echo "window $mode: 4 frames$note"
done

# No DISPLAY in the node's environment: the node's "display" from the config is used.
xvfb-run -a -n $((100 + RANDOM % 800)) -s "-screen 0 640x480x24" sh -c '
  python3 - "$1" "$2" "$DISPLAY" <<PY
import json, sys
c = json.load(open(sys.argv[1]))
c["nodes"][0].update({"output": "window", "stereo": "side-by-side", "display": sys.argv[3]})
json.dump(c, open(sys.argv[2], "w"))
PY
  echo "$DISPLAY" > "$3"
  exec env -u DISPLAY "$4/cavelight-master" --config "$2" --bind "tcp://127.0.0.1:*" --spawn-local --frames 4 \
    --report "$5" --node-args "$6"' sh "$tmp/base.json" "$tmp/nodisplay.json" "$tmp/display" "$build" \
  "$tmp/nodisplay-r.json" "$small_render" 2> "$tmp/nodisplay.log" || { cat "$tmp/nodisplay.log"; fail "no DISPLAY: cluster failed"; }
grep -q "DISPLAY is not set: using $(cat "$tmp/display") (the node's \"display\" in the config)" "$tmp/nodisplay.log" \
  || { cat "$tmp/nodisplay.log"; fail "the node did not say which display it took"; }
[ "$(json 'r["per_node"][0]["frames_ready"]' "$tmp/nodisplay-r.json")" = 4 ] || { cat "$tmp/nodisplay.log"; fail "no DISPLAY: not 4 frames"; }
echo "window without DISPLAY: the config's display $(cat "$tmp/display"), 4 frames"

# The display keys on llvmpipe, where the hardware paths fall back: a monitor by a name that
# is not connected (fullscreen asked: stays windowed), vsync off, an NVIDIA swap group and
# barrier (Mesa has no GLX_NV_swap_group: not joined, the software barrier releases the
# frames), quad-buffered stereo (side-by-side, the window widened); the second node's two
# windows (window per eye) at a position and size. Both project through their MPCDI warp
# and blend (the shipped powerwall-blend example).
root=$(cd "$here/../.." && pwd)
python3 - "$root/configs/clusters/powerwall-blend-local.json" "$tmp/keys.json" <<'PY'
import json, os, sys
c = json.load(open(sys.argv[1]))
for n in c["nodes"]:
    n["screens"][0]["warp"]["mpcdi"] = os.path.join(os.path.dirname(sys.argv[1]), "powerwall-blend.mpcdi")
    n["output"] = "window"
c["nodes"][0].update({"monitor": "DP-9", "fullscreen": True, "vsync": False, "swap_group": 1, "swap_barrier": 1})
c["nodes"][1].update({"stereo": "window-per-eye", "position": [10, 20], "size": [200, 100]})
json.dump(c, open(sys.argv[2], "w"))
PY
xvfb-run -a -n $((100 + RANDOM % 800)) -s "-screen 0 640x480x24" "$build/cavelight-master" --config "$tmp/keys.json" \
  --bind 'tcp://127.0.0.1:*' --spawn-local --frames 4 --report "$tmp/keys-r.json" 2> "$tmp/keys.log" \
  || { cat "$tmp/keys.log"; fail "display keys: cluster failed"; }
for line in "left: monitor 'DP-9' not found (connected: .*): staying windowed" \
            "left: swap group 1: not joined: the GLX driver has no GLX_NV_swap_group .*; frames are released by the software barrier alone" \
            "left: the driver offers no quad-buffered window: showing side-by-side" \
            "left: window 320x150 at .*, vsync off (swap interval 0)" \
            "right: window 200x100 at (10, 20).*, vsync on (swap interval 1)" \
            "right: window 200x100 at (210, 20).*, vsync on (swap interval 1)"; do
  grep -q "cavelight-node $line" "$tmp/keys.log" || { cat "$tmp/keys.log"; fail "display keys: no line '$line'"; }
done
for n in 0 1; do
  [ "$(json "r[\"per_node\"][$n][\"frames_ready\"]" "$tmp/keys-r.json")" = 4 ] || { cat "$tmp/keys.log"; fail "display keys: node $n not 4 frames"; }
done
grep "swap group" "$tmp/keys.log" | sed 's/^/display keys: /'

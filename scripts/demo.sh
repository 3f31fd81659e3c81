#!/usr/bin/env bash
# The demo: a 5-sided 3 m CAVE (10 render nodes, each half a wall, stereo) as a local
# virtual cluster on this machine, headless, on the built-in room, for a few seconds of
# the scripted head and lamp path (master/script.h). Writes per-screen per-eye images,
# the unfolded CAVE in one PNG and a JSON report (frames, per-node pass times, barrier
# waits, bytes sent).
# Usage: scripts/demo.sh [OUT_DIR [MASTER-OPTIONS...]]   (default out/demo)
#   MASTER-OPTIONS go to cavelight-master as well (e.g. --keep-frames).
#   CAVELIGHT_BUILD=DIR: run the programs already built in DIR (no package check, no build).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
if [ -n "${CAVELIGHT_BUILD:-}" ]; then
  build=$(cd "$CAVELIGHT_BUILD" && pwd)
else
  . "$root/scripts/deps.sh"
  cavelight_install_deps
  cavelight_build "$root" >/dev/null
  build=$root/build
fi
out=${1:-$root/out/demo}
shift $(( $# > 0 ? 1 : 0 ))
mkdir -p "$out"
rm -f "$out"/*.png "$out"/report.json

# 48 frames of simulated time at 12 frames per second: 4 seconds of the path (the lamp
# glides for 2 s, then rests), on walls of 256 x 256 pixels (128 x 256 per half wall).
# One LPV thread per node (10 nodes share the cores), a 24-cell lattice and 128x128 RSMs;
# the exposure from the lamp's power. With a display, a window on the master shows the
# walls live (--preview).
"$build/cavelight-master" \
  --config "$root/configs/clusters/cave5-local.json" --spawn-local \
  --frames 48 --dt 0.0833333 \
  --output png --out "$out" --overview "$out/overview.png" --report "$out/report.json" --exposure auto \
  --lattice 24 --rsm 128 --node-args "--threads 1" ${DISPLAY:+--preview} --quiet "$@"

python3 - "$out/report.json" <<'PY' 2>/dev/null || true
import json, sys
r = json.load(open(sys.argv[1]))
print("frames %d, nodes %d, desyncs %d, round trip median %.1f ms, barrier wait median %.1f ms, %d bytes sent"
      % (r["frames"], r["nodes_live_max"], r["desyncs"], r["round_trip_ms"]["median"],
         r["barrier_wait_ms"]["median"], r["bytes_sent"]))
PY
echo "demo: images in $out/ (SCREEN-left.png, SCREEN-right.png), overview $out/overview.png, report $out/report.json"

#!/usr/bin/env bash
# The display paths that llvmpipe only falls back on, tried on a GPU host (docs/deploy.md):
#   1. the presentation pass (warp and blend) on the GPU's own EGL driver: test_present;
#   2. a window on the GPU's GLX driver: a 1-node stereo cluster with quad buffers, vsync
#      and an NVIDIA swap group and barrier, whose node says what it got: quad-buffered or
#      side-by-side, and the swap group joined or not and why.
# The X server: DISPLAY when it answers; else, as root with NVIDIA's Xorg driver installed,
# a private Xorg on the first NVIDIA GPU with a virtual screen (no monitor needed); else a
# private Xvfb (Mesa's GLX: the fallbacks again, and the script says so).
# Usage: scripts/check_display_gpu.sh [BUILD_DIR]   (default build/). Prints "check:" lines;
# exits 1 when a check could not run at all.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
tmp=$(mktemp -d "${TMPDIR:-/tmp}/cavelight-gpu.XXXXXX")
xpid=""
cleanup() {
  [ -n "$xpid" ] && kill "$xpid" 2>/dev/null && wait "$xpid" 2>/dev/null
  rm -rf "$tmp"
}
trap cleanup EXIT
say() { echo "check: $*"; }

command -v nvidia-smi >/dev/null && say "GPU: $(nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | head -1)" \
  || say "GPU: nvidia-smi not found"

# 1. The presentation pass on the headless EGL driver (PNG output read back).
if (cd "$build" && ./test_present > "$tmp/present.log" 2>&1); then
  say "presentation pass (warp, blend, 3d warp) on EGL: passed ($(grep -m1 'blend: worst' "$tmp/present.log"))"
else
  say "presentation pass on EGL: FAILED, its log:"; tail -20 "$tmp/present.log"
fi

# 2. An X server with the GPU's GLX when one can be had.
xorg_nvidia() {
  [ "$(id -u)" = 0 ] && command -v Xorg >/dev/null && command -v nvidia-smi >/dev/null || return 1
  ls /usr/lib/xorg/modules/drivers/nvidia_drv.so /usr/lib/x86_64-linux-gnu/nvidia/xorg/nvidia_drv.so \
     2>/dev/null | grep -q . || { say "Xorg: NVIDIA's Xorg driver (nvidia_drv.so) is not installed"; return 1; }
  local bus; bus=$(nvidia-smi --query-gpu=pci.bus_id --format=csv,noheader | head -1)  # 00000000:18:00.0
  IFS=':.' read -r _ b d f <<< "$bus"
  cat > "$tmp/xorg.conf" <<CONF
Section "Device"
    Identifier "gpu"
    Driver "nvidia"
    BusID "PCI:$((16#$b)):$((16#$d)):$((16#$f))"
    Option "AllowEmptyInitialConfiguration" "True"
    Option "UseDisplayDevice" "None"
EndSection
Section "Screen"
    Identifier "screen"
    Device "gpu"
    DefaultDepth 24
    SubSection "Display"
        Depth 24
        Virtual 1280 1024
    EndSubSection
EndSection
CONF
  Xorg :97 -config "$tmp/xorg.conf" -noreset -nolisten tcp -logfile "$tmp/Xorg.log" > /dev/null 2>&1 &
  xpid=$!
  for _ in $(seq 100); do [ -S /tmp/.X11-unix/X97 ] && break; sleep 0.1; done
  if [ -S /tmp/.X11-unix/X97 ] && kill -0 "$xpid" 2>/dev/null; then export DISPLAY=:97; return 0; fi
  say "Xorg on the NVIDIA GPU did not start; the end of its log:"; tail -5 "$tmp/Xorg.log"
  xpid=""
  return 1
}
xvfb() {
  command -v Xvfb >/dev/null || return 1
  exec 3> "$tmp/display"
  Xvfb -displayfd 3 -noreset -screen 0 1280x1024x24 -nolisten tcp > /dev/null 2>&1 &
  xpid=$!
  for _ in $(seq 100); do grep -q . "$tmp/display" 2>/dev/null && break; sleep 0.1; done
  exec 3>&-
  export DISPLAY=":$(head -1 "$tmp/display")"
}
if [ -n "${DISPLAY:-}" ] && command -v xdpyinfo >/dev/null && xdpyinfo > /dev/null 2>&1; then
  say "X server: the running one at DISPLAY=$DISPLAY"
elif xorg_nvidia; then
  say "X server: a private Xorg on the NVIDIA GPU, virtual screen 1280x1024 (DISPLAY=$DISPLAY)"
elif xvfb; then
  say "X server: a private Xvfb (DISPLAY=$DISPLAY): Mesa's GLX, not the GPU's; the window checks show the fallbacks only"
else
  say "no X server could be had (no DISPLAY, no NVIDIA Xorg driver, no Xvfb)"; exit 1
fi

# The window's GL driver, as the standalone node reports it.
"$build/cavelight-node" --standalone --gl glfw --frames 1 --width 64 --height 48 --gi none > "$tmp/glfw.log" 2>&1 \
  && say "window GL: $(grep -m1 'cavelight-node: GLFW window' "$tmp/glfw.log" | cut -d, -f2-3)" \
  || { say "a GLFW window could not be made:"; tail -3 "$tmp/glfw.log"; }

# A stereo node with quad buffers, vsync, swap group 1 and barrier 1, 60 frames.
python3 - "$root/configs/clusters/desktop-local.json" "$tmp/gpu.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
n = c["nodes"][0]
n.update({"output": "window", "eyes": "stereo", "stereo": "quad", "vsync": True, "swap_group": 1, "swap_barrier": 1})
n.pop("display", None)
json.dump(c, open(sys.argv[2], "w"))
PY
if (cd "$tmp" && "$build/cavelight-master" --config "$tmp/gpu.json" --bind 'tcp://127.0.0.1:*' --spawn-local \
      --frames 60 --gi none --report "$tmp/report.json" > "$tmp/cluster.log" 2>&1); then
  say "$(grep -m1 -o 'window [0-9]*x[0-9]* .*' "$tmp/cluster.log")"
  grep -q "no quad-buffered window" "$tmp/cluster.log" && say "quad buffers: none offered (side-by-side shown)" \
    || say "quad buffers: offered"
  say "$(grep -m1 -o 'swap group 1: .*' "$tmp/cluster.log" || echo 'swap group 1: no line from the node')"
  say "$(grep -m1 -o '[0-9]* frames in [0-9.]* s.*' "$tmp/cluster.log")"
else
  say "the window cluster failed; its log:"; tail -20 "$tmp/cluster.log"; exit 1
fi

#!/usr/bin/env bash
# Input that degrades instead of stopping: a master whose input config names a USB gamepad
# that is not plugged in says so once, with the retry, and runs every frame with the
# remaining sources (here a recording that moves the head).
here=$(cd "$(dirname "$0")" && pwd)
. "$here/cluster_lib.sh"
root=$(cd "$here/../.." && pwd)

make_config "$tmp/c1.json" 20000 a
cat > "$tmp/input.json" <<JSON
{"sources": [
  {"type": "usb", "name": "pad", "vendor": "0xfffe", "product": "0x1234", "reconnect": 0.2,
   "buttons": [{"byte": 1, "bit": 0, "to": "C"}]},
  {"type": "playback", "file": "$root/configs/input/demo-session.txt", "realtime": true, "loop": true}]}
JSON
"$build/cavelight-master" --config "$tmp/c1.json" --bind 'tcp://127.0.0.1:*' --spawn-local --render none \
  --input "$tmp/input.json" --frames 30 --fps 20 --out "$tmp/out" --report "$tmp/r.json" 2> "$tmp/master.log" \
  || { cat "$tmp/master.log"; fail "the master stopped for a missing gamepad"; }
[ "$(json 'r["frames"]' "$tmp/r.json")" = 30 ] || { cat "$tmp/master.log"; fail "not 30 frames"; }
grep -q "input pad: \(no USB device fffe:1234 found\|cannot start libusb\).*; retrying every 0.2 s" "$tmp/master.log" \
  || { cat "$tmp/master.log"; fail "no warning naming the missing gamepad and the retry"; }
[ "$(grep -c "input pad:" "$tmp/master.log")" = 1 ] || { cat "$tmp/master.log"; fail "the missing gamepad was reported more than once"; }
echo "a missing USB gamepad: one warning with the retry, 30 frames"

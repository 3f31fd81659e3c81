#!/usr/bin/env bash
# The GI method switched live by the renderer-settings layout (the paper's "switch
# pipeline"): a recorded wand goes to the settings layout and presses C twice (ILPV ->
# none -> vpl). Two rendering nodes switch in the same frame: no desync in any frame, the
# none frames report none's constant checksum on both nodes, and the session ends on vpl
# with equal VPL checksums. Then --gi none and --gi vpl on the master start every node on
# that method, the vpl nodes with equal checksums in every frame, and --vpl-selection view
# keeps them equal.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/cluster_lib.sh"

make_config "$tmp/c2.json" 30000 a b
# poll blocks: 1..3 ILPV, R twice (settings), C at poll 7 -> none, C at poll 10 -> vpl.
{
  echo "cavelight-input 1"
  echo "head 0 0 1.7 0 1 0 0 0 1 0 0 0 1"
  echo "wand 0 0.2 1.3 -0.4 1 0 0 0 1 0 0 0 1"
  echo "poll 0 0"
  t=0
  for i in $(seq 1 13); do
    t=$(python3 -c "print($i / 30)")
    case $i in
      3|5) echo "buttons $t 4 4" ;;   # R: next layout
      7|10) echo "buttons $t 8 8" ;;  # C: next GI method
      4|6|8|11) echo "buttons $t 0 0" ;;
    esac
    echo "poll $t 0.0333333333"
  done
} > "$tmp/switch.txt"
none=8e37b614dbd95475   # gi_none.c: FNV-1a of "none"
run() { # frames report
  "$build/cavelight-master" --config "$tmp/c2.json" --bind 'tcp://127.0.0.1:*' --spawn-local \
    --input "$tmp/switch.txt" ${1:+--frames $1} --report "$2" --node-args "$small_render" --vpl-count 64 --quiet \
    2> "$tmp/master.log" || { cat "$tmp/master.log"; fail "master failed"; }
  [ "$(json 'r["desyncs"]' "$2")" = 0 ] || { cat "$tmp/master.log"; fail "desync while switching"; }
  [ "$(json 'len(set(n["last_checksum"] for n in r["per_node"]))' "$2")" = 1 ] || fail "checksums differ"
}
run 9 "$tmp/r_none.json"   # ends in the none frames
[ "$(json 'r["per_node"][0]["last_checksum"]' "$tmp/r_none.json")" = $none ] || fail "frame 9 is not on none"
run "" "$tmp/r_vpl.json"   # the whole recording: on to vpl
[ "$(json 'r["frames"]' "$tmp/r_vpl.json")" -ge 12 ] || fail "the recording did not run to its end"
[ "$(json 'r["per_node"][0]["last_checksum"]' "$tmp/r_vpl.json")" != $none ] || fail "not on vpl"
echo "live switch ILPV -> none -> vpl on 2 nodes: no desync"

"$build/cavelight-master" --config "$tmp/c2.json" --bind 'tcp://127.0.0.1:*' --spawn-local --gi none \
  --frames 3 --report "$tmp/r_gi.json" --node-args "$small_render" --quiet 2> "$tmp/m2.log" \
  || { cat "$tmp/m2.log"; fail "master --gi none failed"; }
[ "$(json 'r["per_node"][1]["last_checksum"]' "$tmp/r_gi.json")" = $none ] || fail "--gi none not applied"
bad=$("$build/cavelight-master" --config "$tmp/c2.json" --gi bogus 2>&1 || true)
grep -q -- "--gi bogus: expected one of ilpv, none, vpl or ldm" <<< "$bad" || fail "bad --gi accepted: $bad"
echo "--gi none on the master: every node on none"

"$build/cavelight-master" --config "$tmp/c2.json" --bind 'tcp://127.0.0.1:*' --spawn-local --gi vpl \
  --vpl-count 64 --frames 3 --report "$tmp/r_v.json" --node-args "$small_render" --quiet 2> "$tmp/m3.log" \
  || { cat "$tmp/m3.log"; fail "master --gi vpl failed"; }
[ "$(json 'r["desyncs"]' "$tmp/r_v.json")" = 0 ] || { cat "$tmp/m3.log"; fail "vpl nodes desynced"; }
[ "$(json 'len(set(n["last_checksum"] for n in r["per_node"]))' "$tmp/r_v.json")" = 1 ] || fail "vpl checksums differ"
[ "$(json 'r["per_node"][1]["last_checksum"]' "$tmp/r_v.json")" != $none ] || fail "--gi vpl not applied"
bad=$("$build/cavelight-master" --config "$tmp/c2.json" --vpl-count 5000 2>&1 || true)
grep -q -- "--vpl-count 5000: expected a whole number in 64..4096" <<< "$bad" || fail "bad --vpl-count accepted: $bad"
echo "--gi vpl on the master: 2 nodes with equal VPL checksums in every frame"

# The view rule on the master: the nodes choose by what the scripted head sees, each from
# the same store, so they still agree in every frame; the VPLs are other than flux's.
"$build/cavelight-master" --config "$tmp/c2.json" --bind 'tcp://127.0.0.1:*' --spawn-local --gi vpl \
  --vpl-count 64 --vpl-selection view --frames 3 --report "$tmp/r_view.json" --node-args "$small_render" \
  --quiet 2> "$tmp/m4.log" || { cat "$tmp/m4.log"; fail "master --vpl-selection view failed"; }
[ "$(json 'r["desyncs"]' "$tmp/r_view.json")" = 0 ] || { cat "$tmp/m4.log"; fail "view-rule nodes desynced"; }
[ "$(json 'len(set(n["last_checksum"] for n in r["per_node"]))' "$tmp/r_view.json")" = 1 ] || fail "view checksums differ"
[ "$(json 'r["per_node"][0]["last_checksum"]' "$tmp/r_view.json")" != \
  "$(json 'r["per_node"][0]["last_checksum"]' "$tmp/r_v.json")" ] || fail "--vpl-selection view not applied"
bad=$("$build/cavelight-master" --config "$tmp/c2.json" --vpl-selection best 2>&1 || true)
grep -q -- "--vpl-selection best: expected one of flux, view or regular" <<< "$bad" || fail "bad --vpl-selection accepted: $bad"
echo "--vpl-selection view on the master: 2 nodes with equal VPL checksums in every frame"

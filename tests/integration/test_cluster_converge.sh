#!/usr/bin/env bash
# Frame skipping in a 3-node cluster: with a static scene (a recorded input in which
# nothing moves) every node skips the same converged frames, so the LPV checksums stay
# equal (no desyncs); with skipping off the LPV keeps creeping below the threshold and
# ends on a different checksum, which shows that frames were skipped.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/cluster_lib.sh"

make_config "$tmp/c3.json" 20000 a b c
{ echo "cavelight-input 1"; for i in $(seq 0 70); do echo "poll $i 0.0333"; done; } > "$tmp/static.rec"
run() { # REPORT EXTRA_MASTER_ARGS
  "$build/cavelight-master" --config "$tmp/c3.json" --bind 'tcp://127.0.0.1:*' --spawn-local \
    --frames 60 --wait-ms 120000 --input "$tmp/static.rec" --output headless --report "$1" \
    --node-args "$small_render" $2 --quiet 2> "$tmp/master.log" || { cat "$tmp/master.log"; fail "master failed ($2)"; }
  [ "$(json 'r["desyncs"]' "$1")" = 0 ] || fail "desync between nodes ($2)"
  [ "$(json 'min(n["frames_ready"] for n in r["per_node"])' "$1")" = 60 ] || fail "a node missed frames ($2)"
  [ "$(json 'len(set(n["last_checksum"] for n in r["per_node"]))' "$1")" = 1 ] || fail "checksums differ ($2)"
}
run "$tmp/skip.json" ""
run "$tmp/full.json" "--converge-threshold -1"
skip=$(json 'r["per_node"][0]["last_checksum"]' "$tmp/skip.json")
full=$(json 'r["per_node"][0]["last_checksum"]' "$tmp/full.json")
[ "$skip" != "$full" ] || fail "the same checksum with and without skipping: nothing was skipped"
echo "static cluster, 60 frames: mean frame pass per node (ms) with skipping" \
  "$(json '[round(n["pass_ms_mean"]["frame_pass"], 2) for n in r["per_node"]]' "$tmp/skip.json"), without" \
  "$(json '[round(n["pass_ms_mean"]["frame_pass"], 2) for n in r["per_node"]]' "$tmp/full.json")"

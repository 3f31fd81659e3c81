#!/usr/bin/env bash
# A 3-node local cluster end to end with real rendering: spawned node processes, equal
# LPV checksums on every node in every frame (the master counts any difference as a
# desync), per-screen per-eye images, the overview and the report. Then the same with one
# node reporting a wrong checksum, to show the desync check fires.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/cluster_lib.sh"

make_config "$tmp/c3.json" 20000 a b c
"$build/cavelight-master" --config "$tmp/c3.json" --bind 'tcp://127.0.0.1:*' --spawn-local \
  --frames 10 --output png --out "$tmp/img" --overview "$tmp/img/overview.png" \
  --report "$tmp/r.json" --node-args "$small_render" --quiet 2> "$tmp/master.log" || { cat "$tmp/master.log"; fail "master failed"; }
[ "$(json 'r["frames"]' "$tmp/r.json")" = 10 ] || fail "not 10 frames"
[ "$(json 'r["desyncs"]' "$tmp/r.json")" = 0 ] || { cat "$tmp/master.log"; fail "desync between nodes"; }
[ "$(json 'min(n["frames_ready"] for n in r["per_node"])' "$tmp/r.json")" = 10 ] || fail "a node missed frames"
[ "$(json 'len(set(n["last_checksum"] for n in r["per_node"]))' "$tmp/r.json")" = 1 ] || fail "checksums differ"
[ "$(json 'min(n["pass_ms_mean"]["frame_pass"] for n in r["per_node"]) > 0' "$tmp/r.json")" = True ] || fail "no frame pass timings"
for s in front-l front-r left-f; do for e in left right; do
  [ -s "$tmp/img/$s-$e.png" ] || fail "missing image $s-$e.png"
done; done
[ -s "$tmp/img/overview.png" ] || fail "missing overview"
echo "3 nodes, 10 frames, equal checksums: $(json 'r["per_node"][0]["last_checksum"]' "$tmp/r.json")"

# The check can fail: node b lies about its checksum from frame 4 on (stub rendering).
"$build/cavelight-master" --config "$tmp/c3.json" --bind 'tcp://127.0.0.1:*' --endpoint-file "$tmp/ep" \
  --frames 8 --report "$tmp/r2.json" --quiet 2> "$tmp/master2.log" &
pids+=($!)
wait_for_file "$tmp/ep" 10
for n in a b c; do
  extra=""; [ $n = b ] && extra="--fault-checksum-from 4"
  "$build/cavelight-node" --cluster "$tmp/c3.json" --name $n --master "$(cat "$tmp/ep")" --render none \
    --exit-with-master --quiet $extra &
  pids+=($!)
done
wait "${pids[0]}" || fail "master (fault run) failed"
[ "$(json 'r["desyncs"]' "$tmp/r2.json")" = 5 ] || fail "expected 5 desync frames, got $(json 'r["desyncs"]' "$tmp/r2.json")"
grep -q "desync in frame 4" "$tmp/master2.log" || fail "desync not reported in the log"
echo "desync detected in frames 4..8 as expected"

# --spawn-remote goes through the config's launch template ({host}, {command}); here the
# "remote shell" is a local sh that records the host it was given.
python3 - "$tmp/c3.json" "$tmp/remote.json" "$tmp" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c["launch"] = "echo {host} >> " + sys.argv[3] + "/hosts; exec sh -c {command}"
for i, n in enumerate(c["nodes"]): n["host"] = "render%d.example" % i
json.dump(c, open(sys.argv[2], "w"))
PY
"$build/cavelight-master" --config "$tmp/remote.json" --bind 'tcp://127.0.0.1:*' --spawn-remote --render none \
  --frames 20 --report "$tmp/r3.json" --quiet 2> "$tmp/master3.log" || { cat "$tmp/master3.log"; fail "spawn-remote failed"; }
[ "$(json 'min(n["frames_ready"] for n in r["per_node"])' "$tmp/r3.json")" = 20 ] || fail "remote-launched nodes missed frames"
[ "$(sort "$tmp/hosts" | tr '\n' ' ')" = "render0.example render1.example render2.example " ] || fail "launch template hosts: $(cat "$tmp/hosts")"
echo "spawn-remote through the launch template: 3 nodes, 20 frames"

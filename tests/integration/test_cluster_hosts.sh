#!/usr/bin/env bash
# Real hosts: --spawn-remote runs each node's own program in its own working folder with
# its own copy of the config (no identical paths); each started node logs to
# OUT/logs/NODE.log; the wait for nodes names the missing ones, and a node that fails to
# start is reported with the end of its log instead of being waited for; a node killed
# during the session is reported with its signal, and the session goes on.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/cluster_lib.sh"

make_config "$tmp/c3.json" 20000 a b c
mkdir -p "$tmp/host-b/bin" "$tmp/host-b/work"
ln -s "$build/cavelight-node" "$tmp/host-b/bin/node-program"
cp "$tmp/c3.json" "$tmp/host-b/work/cave.json"
python3 - "$tmp/c3.json" "$tmp/remote.json" "$tmp" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
t = sys.argv[3]
# The "remote shell" is a local sh that notes each command it was given.
c["launch"] = "echo {command} >> " + t + "/commands; exec sh -c {command}"
c["nodes"][1].update({"host": "render-b", "exe": t + "/host-b/bin/node-program",
                      "workdir": t + "/host-b/work", "config": "cave.json"})
json.dump(c, open(sys.argv[2], "w"))
PY
cp "$tmp/remote.json" "$tmp/host-b/work/cave.json" # the same file on "host b"
"$build/cavelight-master" --config "$tmp/remote.json" --bind 'tcp://127.0.0.1:*' --spawn-remote --render none \
  --frames 20 --out "$tmp/out" --report "$tmp/r.json" 2> "$tmp/master.log" || { cat "$tmp/master.log"; fail "spawn-remote failed"; }
[ "$(json 'min(n["frames_ready"] for n in r["per_node"])' "$tmp/r.json")" = 20 ] || fail "a node missed frames"
grep -q "^cd '$tmp/host-b/work' && exec '$tmp/host-b/bin/node-program' '--cluster' 'cave.json' '--name' 'b' " "$tmp/commands" \
  || { cat "$tmp/commands"; fail "node b was not started with its own program, folder and config"; }
for n in a b c; do
  grep -q "cavelight-node $n: 20 frames" "$tmp/out/logs/$n.log" || { cat "$tmp/out/logs/$n.log"; fail "no log of node $n"; }
done
echo "spawn-remote: node b from its own program, folder and config; logs in out/logs"

# A node that cannot start: reported with its log at once, the others go on.
python3 - "$tmp/remote.json" "$tmp/broken.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c["nodes"][2]["exe"] = "/nonexistent/cavelight-node"
json.dump(c, open(sys.argv[2], "w"))
PY
cp "$tmp/broken.json" "$tmp/host-b/work/cave.json"
start=$(date +%s)
"$build/cavelight-master" --config "$tmp/broken.json" --bind 'tcp://127.0.0.1:*' --spawn-remote --render none \
  --frames 5 --wait-ms 600000 --out "$tmp/out2" --report "$tmp/r2.json" 2> "$tmp/master2.log" \
  || { cat "$tmp/master2.log"; fail "the master stopped for one broken node"; }
[ $(( $(date +%s) - start )) -lt 300 ] || fail "the master waited the whole --wait-ms for a node that had exited"
grep -q "node c exited with status 127 before joining; the end of its log $tmp/out2/logs/c.log" "$tmp/master2.log" \
  || { cat "$tmp/master2.log"; fail "the failed node was not reported"; }
grep -q "c|.*nonexistent" "$tmp/master2.log" || fail "the failed node's log was not shown"
[ "$(json 'r["frames"]' "$tmp/r2.json")" = 5 ] || fail "no frames without node c"
echo "a node that cannot start: reported with its log, the session goes on"
python3 - "$tmp/remote.json" "$tmp/none.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
for n in c["nodes"]:
    n["exe"] = "/nonexistent/cavelight-node"
json.dump(c, open(sys.argv[2], "w"))
PY
start=$(date +%s)
"$build/cavelight-master" --config "$tmp/none.json" --bind 'tcp://127.0.0.1:*' --spawn-remote --render none \
  --frames 5 --wait-ms 600000 --out "$tmp/out5" 2> "$tmp/master5.log" && fail "the master succeeded without nodes"
[ $(( $(date +%s) - start )) -lt 300 ] || fail "the master waited for nodes that had all exited"
grep -q "no node is live and every started node has ended: stopping" "$tmp/master5.log" \
  || { cat "$tmp/master5.log"; fail "no line saying why the master stopped"; }
echo "no node can start: the master stops at once, saying why"

# Nodes started by hand, one missing: the wait names it while it waits (every 5 s) and when
# it ends (here: stopped by SIGTERM once the other two have joined, however long that took).
# wait_log FILE PATTERN: until FILE holds PATTERN (at most 120 s).
wait_log() {
  for _ in $(seq 1200); do grep -q -- "$2" "$1" && return 0; sleep 0.1; done
  cat "$1"; fail "no '$2' in $1"
}
"$build/cavelight-master" --config "$tmp/c3.json" --bind 'tcp://127.0.0.1:*' --endpoint-file "$tmp/ep" \
  --frames 3 --wait-ms 600000 --report "$tmp/r3.json" 2> "$tmp/master3.log" &
master=$!
pids+=($master)
wait_for_file "$tmp/ep" 10
for n in a b; do
  "$build/cavelight-node" --cluster "$tmp/c3.json" --name $n --master "$(cat "$tmp/ep")" --render none \
    --exit-with-master --quiet &
  pids+=($!)
done
wait_log "$tmp/master3.log" "2 of 3 nodes joined; waiting up to [0-9]* s more for c (localhost)$"
kill -TERM "$master"
wait "$master" || { cat "$tmp/master3.log"; fail "master failed"; }
grep -q "2 of 3 nodes joined within [0-9]* ms; missing: c (localhost); going on without them" "$tmp/master3.log" \
  || { cat "$tmp/master3.log"; fail "the missing node was not named at the end of the wait"; }
echo "the wait names the missing node"

# A node that dies during the session: named with its signal at once, the others go on.
make_config "$tmp/c3s.json" 1500 a b c
"$build/cavelight-master" --config "$tmp/c3s.json" --bind 'tcp://127.0.0.1:*' --spawn-local --render none \
  --frames 0 --fps 10 --out "$tmp/out4" --report "$tmp/r4.json" 2> "$tmp/master4.log" &
master=$!
pids+=($master)
wait_log "$tmp/master4.log" "3 nodes live, running until stopped"
node_b=$(pgrep -f -- "--cluster $tmp/c3s.json --name b ") || fail "node b is not running"
kill -9 "$node_b"
wait_log "$tmp/master4.log" "node b was killed by signal 9 ([A-Za-z]*) during the session; going on with the others"

wait_log "$tmp/master4.log" "node b \(disconnected: dropped\|not ready\)"
sleep 2
kill -TERM "$master"
wait "$master" || { cat "$tmp/master4.log"; fail "the master failed after losing node b"; }
[ "$(json 'r["frames"] > 10' "$tmp/r4.json")" = True ] || { cat "$tmp/master4.log"; fail "the session did not go on"; }
[ "$(grep -c "node b was killed" "$tmp/master4.log")" = 1 ] || fail "node b's end was reported more than once"
! grep -q "node [ac] \(was killed\|exited\)" "$tmp/master4.log" || { cat "$tmp/master4.log"; fail "a node that left after BYE was reported"; }
echo "a node killed during the session: reported once with its signal, $(json 'r["frames"]' "$tmp/r4.json") frames"

#!/usr/bin/env bash
# What the master says, and when: a normal end of a session is no drop (no "disconnected"
# line, three runs of rendering nodes), a node stopped during the session "left"; lines
# that spawned nodes print are relayed naming their node, --quiet too; security "insecure"
# is refused on an endpoint outside the loopback range unless --insecure-anywhere, and its
# warning names the endpoint actually bound; "no node is live" is rate-limited while a
# stranger makes a node come and go hundreds of times.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/cluster_lib.sh"

make_config "$tmp/c.json" 5000 a b
# A normal end, three times: nodes leave after the master's BYE, nobody is dropped.
for run in 1 2 3; do
  "$build/cavelight-master" --config "$tmp/c.json" --bind 'tcp://127.0.0.1:*' --spawn-local --frames 3 \
    --out "$tmp/end$run" --node-args "$small_render" 2> "$tmp/end$run.log" \
    || { cat "$tmp/end$run.log"; fail "run $run failed"; }
  grep -q "disconnected\|dropped" "$tmp/end$run.log" && { cat "$tmp/end$run.log"; fail "run $run: a normal end reported a drop"; }
  grep -q "0 drops" "$tmp/end$run.log" || fail "run $run: no summary"
done
echo "3 normal ends: no node reported dropped"

# A node stopped (SIGTERM) during the session says BYE: it left, it was not dropped.
rm -f "$tmp/ep"
"$build/cavelight-master" --config "$tmp/c.json" --bind 'tcp://127.0.0.1:*' --endpoint-file "$tmp/ep" --frames 0 \
  --fps 30 2> "$tmp/leave.log" &
master=$!; pids+=($master)
wait_for_file "$tmp/ep" 20
"$build/cavelight-node" --cluster "$tmp/c.json" --name a --master "$(cat "$tmp/ep")" --render none 2> /dev/null &
node=$!; pids+=($node)
for _ in $(seq 200); do grep -q "node a joined" "$tmp/leave.log" && break; sleep 0.05; done
sleep 0.3
kill -TERM $node; wait $node || fail "node a failed on SIGTERM"
for _ in $(seq 100); do grep -q "node a left\|node a disconnected" "$tmp/leave.log" && break; sleep 0.05; done
kill -TERM $master; wait $master || true
grep -q "node a left" "$tmp/leave.log" && ! grep -q "node a disconnected" "$tmp/leave.log" \
  || { cat "$tmp/leave.log"; fail "a node that said BYE was not reported as leaving"; }
echo "a node stopped during the session: 'left'"

# Relayed lines name their node, with --quiet too: the launch command prints a warning
# without a node name and a line of its own before it starts the node.
python3 - "$tmp/c.json" "$tmp/relay.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c["launch"] = "echo 'cavelight-node: warning: unnamed' >&2; echo 'a plain line' >&2; exec sh -c {command}"
json.dump(c, open(sys.argv[2], "w"))
PY
"$build/cavelight-master" --config "$tmp/relay.json" --bind 'tcp://127.0.0.1:*' --spawn-remote --render none \
  --frames 3 --quiet --out "$tmp/relay" 2> "$tmp/relay.log" || { cat "$tmp/relay.log"; fail "relay run failed"; }
for n in a b; do
  grep -q "^cavelight-node $n: warning: unnamed$" "$tmp/relay.log" && grep -q "^$n| a plain line$" "$tmp/relay.log" \
    || { cat "$tmp/relay.log"; fail "node $n's relayed lines do not name it"; }
  grep -q "^cavelight-node: warning: unnamed$" "$tmp/relay/logs/$n.log" || fail "node $n's log file was changed"
done
grep -q "^cavelight-node: " "$tmp/relay.log" && fail "an unnamed node line reached the master's output"
echo "relayed lines name their node (--quiet)"

# Insecure mode: the warning names the bound endpoint (a '*' port resolved), a bind outside
# the loopback range is refused in one line, and taken with --insecure-anywhere.
"$build/cavelight-master" --config "$tmp/c.json" --bind 'tcp://127.0.0.1:*' --endpoint-file "$tmp/ep2" --frames 1 \
  --wait-ms 100 2> "$tmp/warn.log" || true
grep -q "any peer that reaches $(cat "$tmp/ep2") may join" "$tmp/warn.log" \
  || { cat "$tmp/warn.log"; fail "the insecure warning does not name the bound endpoint $(cat "$tmp/ep2")"; }
set +e
"$build/cavelight-master" --config "$tmp/c.json" --bind 'tcp://0.0.0.0:*' --frames 1 --wait-ms 100 2> "$tmp/any.log"
rc=$?
set -e
[ $rc = 1 ] && [ "$(wc -l < "$tmp/any.log")" = 1 ] && grep -q "outside the loopback range.*--insecure-anywhere" "$tmp/any.log" \
  || { cat "$tmp/any.log"; fail "insecure mode on 0.0.0.0 not refused in one line (exit $rc)"; }
"$build/cavelight-master" --config "$tmp/c.json" --bind 'tcp://0.0.0.0:*' --insecure-anywhere --frames 1 --wait-ms 100 \
  2> "$tmp/anyok.log" || true
grep -q 'any peer that reaches tcp://0.0.0.0:[0-9]* may join as a node (--insecure-anywhere)' "$tmp/anyok.log" \
  || { cat "$tmp/anyok.log"; fail "--insecure-anywhere not taken"; }
echo "insecure mode: bound endpoint named; 0.0.0.0 refused, taken with --insecure-anywhere"

# Churn: a stranger says HELLO as node a on 300 fresh connections, each closed at once.
# The master sees a node come and go each time; its "no node is live" line is rate-limited.
make_config "$tmp/one.json" 2000 a
rm -f "$tmp/ep"
"$build/cavelight-master" --config "$tmp/one.json" --bind 'tcp://127.0.0.1:*' --endpoint-file "$tmp/ep" --frames 0 \
  --wait-ms 60000 2> "$tmp/churn.log" &
master=$!; pids+=($master)
wait_for_file "$tmp/ep" 20
start=$SECONDS
"$build/cluster_stranger" --config "$tmp/one.json" --endpoint "$(cat "$tmp/ep")" --attack takeover --key none \
  --victim a --count 300 > "$tmp/churn-stranger.log" 2>&1 || fail "stranger failed"
kill -TERM $master; wait $master || true
idle=$(grep -c "no node is live" "$tmp/churn.log" || true)
most=$(( 5 + (SECONDS - start) / 10 + 1 ))
comings=$(grep -c "node a joined\|node a rejoined\|(.* lines about node a not logged)" "$tmp/churn.log" || true)
[ "$idle" -ge 1 ] && [ "$idle" -le $most ] || { cat "$tmp/churn.log"; fail "$idle 'no node is live' lines (at most $most)"; }
echo "churn: 300 comings and goings, $idle 'no node is live' lines, $comings lines about node a"

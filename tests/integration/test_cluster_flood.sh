#!/usr/bin/env bash
# A flood of unfinished handshakes against a 2-node curve cluster whose master may hold
# only 200 descriptors (a hard limit it cannot raise): a stranger keeps 300 TCP
# connections open from another loopback address that send only the start of a ZMTP
# greeting, and opens a new one whenever the master closes one, for 8 s. Node b is killed
# and restarted during the flood: it must be back within 4 s (before the bound on
# connections no node speaks on, it stayed out until the flood ended: the master had no
# descriptor left). Frames go on, the shut connections are counted in the report, the
# limit is reported, and the master's lines about the flood are rate-limited.
# FLOOD_CONNECTIONS, FLOOD_FD_LIMIT and FLOOD_MS change the figures (a measurement:
# docs/cluster.md); FLOOD_SOURCE=127.0.0.1 floods from the nodes' own address.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/cluster_lib.sh"
flood_ms=${FLOOD_MS:-8000}
connections=${FLOOD_CONNECTIONS:-300}
fd_limit=${FLOOD_FD_LIMIT:-200}
source_addr=${FLOOD_SOURCE:-127.0.0.2}
# The master's CPU time so far in ms (utime + stime of /proc/PID/stat).
cpu_ms() { awk -v hz="$(getconf CLK_TCK)" '{ print int(($14 + $15) * 1000 / hz) }' "/proc/$1/stat"; }

CLUSTER_SECURITY=curve make_config "$tmp/c.json" 3000 a b
"$build/cavelight-master" --config "$tmp/c.json" --keygen 2> "$tmp/keygen.log" || { cat "$tmp/keygen.log"; fail "keygen"; }

# The master raises its soft limit to the hard one and says so.
if [ "$(ulimit -Hn)" = unlimited ] || [ "$(ulimit -Hn)" -gt 256 ]; then
  ( ulimit -Sn 256; exec "$build/cavelight-master" --config "$tmp/c.json" --bind 'tcp://127.0.0.1:*' --frames 1 \
      --wait-ms 100 --report "$tmp/raise.json" 2> "$tmp/raise.log" ) || true
  grep -q "file descriptor limit raised from 256 to" "$tmp/raise.log" || { cat "$tmp/raise.log"; fail "limit not raised"; }
  [ "$(json 'r["fd_limit"] > 256' "$tmp/raise.json")" = True ] || fail "the report's fd_limit is not the raised one"
  echo "descriptor limit: $(grep -o 'raised from 256 to [0-9]*' "$tmp/raise.log")"
fi

( ulimit -n $fd_limit; exec "$build/cavelight-master" --config "$tmp/c.json" --bind 'tcp://127.0.0.1:*' \
    --endpoint-file "$tmp/ep" --frames 0 --fps 30 --report "$tmp/r.json" 2> "$tmp/master.log" ) &
master=$!; pids+=($master)
wait_for_file "$tmp/ep" 20
ep=$(cat "$tmp/ep")
node_b() {
  "$build/cavelight-node" --cluster "$tmp/c.json" --name b --master "$ep" --render none 2> "$tmp/$1" &
  pids+=($!)
}
"$build/cavelight-node" --cluster "$tmp/c.json" --name a --master "$ep" --render none 2> "$tmp/a.log" &
pids+=($!)
node_b b1.log
b1=${pids[-1]}
for _ in $(seq 200); do grep -q "running" "$tmp/master.log" && break; sleep 0.1; done
if [ "$fd_limit" -lt 4096 ]; then
  grep -q "file descriptor limit $fd_limit, the hard limit" "$tmp/master.log" || { cat "$tmp/master.log"; fail "limit not reported"; }
fi

start=$SECONDS
cpu0=$(cpu_ms $master)
"$build/cluster_stranger" --config "$tmp/c.json" --endpoint "$ep" --attack flood --count $connections \
  --source $source_addr --listen-ms $flood_ms > "$tmp/flood.log" 2>&1 &
flood=$!; pids+=($flood)
sleep 1.5
most_fds=0
kill -9 $b1 || { cat "$tmp/b1.log" "$tmp/master.log"; fail "node b ended before it was killed"; }
t0=$(date +%s%N)
node_b b2.log
for _ in $(seq 1000); do
  grep -q "joined the master" "$tmp/b2.log" && break
  fds=$(ls "/proc/$master/fd" 2> /dev/null | wc -l)
  [ "$fds" -gt "$most_fds" ] && most_fds=$fds
  sleep 0.01
done
back=$(( ($(date +%s%N) - t0) / 1000000 ))
grep -q "joined the master" "$tmp/b2.log" || { cat "$tmp/master.log" "$tmp/b2.log"; fail "node b did not rejoin during the flood"; }
kill -0 $flood 2> /dev/null || fail "the flood ended before node b was back ($back ms): no proof"
wait $flood || fail "the flood failed"
cpu=$(( $(cpu_ms $master) - cpu0 ))
sleep 0.5 # frames with both nodes after the flood
kill -TERM $master; wait $master || { cat "$tmp/master.log"; fail "master failed"; }
cat "$tmp/flood.log"
echo "$connections unfinished handshakes from $source_addr for $flood_ms ms: node b restarted during it back after $back ms; master descriptors at most $most_fds of $fd_limit while it rejoined; master CPU $cpu ms during the flood"
[ "$back" -lt 4000 ] || { cat "$tmp/master.log"; fail "node b took $back ms to rejoin during the flood"; }

[ "$(json '(r["drops"], r["joins"], r["desyncs"])' "$tmp/r.json")" = "(1, 3, 0)" ] \
  || { grep -v "wait for a node\|failed its handshake\|cannot accept" "$tmp/master.log"; fail "drops, joins, desyncs: $(json '(r["drops"], r["joins"], r["desyncs"])' "$tmp/r.json")"; }
[ "$(json '[n["state"] for n in r["per_node"]]' "$tmp/r.json")" = "['live', 'live']" ] || fail "a node is not live at the end"
[ "$(json "r['unauthenticated_dropped'] > 0 and r['fd_limit'] == $fd_limit" "$tmp/r.json")" = True ] \
  || fail "the report lacks the shut connections or the limit"
echo "report: $(json '(r["frames"], r["unauthenticated_dropped"], r["accept_failures"], r["handshakes_failed"])' "$tmp/r.json") (frames, shut by the bound, accept failures, failed handshakes)"
# Each kind of line about the flood: the first 5, then one per 10 s.
most=$(( 5 + (SECONDS - start) / 10 + 1 ))
for kind in "wait for a node's first message" "cannot accept" "failed its handshake"; do
  n=$(grep -c "$kind" "$tmp/master.log" || true)
  [ "$n" -le $most ] || fail "$n lines '$kind' (at most $most)"
done

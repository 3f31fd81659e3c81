#!/usr/bin/env bash
# A 2-node cluster in curve mode against a stranger who has the config file and the
# master's public key but no node key (tests/cluster/cluster_stranger.c): without CURVE,
# with a key of its own, with node b's stolen public key and a random secret key, and as an
# insider holding node b's real key pair, it tries a routing-id takeover of node a, reading
# the stream, forged READYs and a HELLO flood while frames run; it replays node b's
# captured CURVE traffic (handshake, HELLO, READYs) to the master on new connections; then
# it poses as the master, with a key of its own or none, to nodes waiting for one. Nothing
# may change: same frames, same final parameters (the nodes' checksums equal a run without
# the stranger), no join, drop or desync, the stranger gets no message, and the nodes say
# why the fake master's handshakes fail. In insecure mode a fake master's hostile
# parameters are clamped, not fatal, and a node cut off by a stranger's message under its
# name is back within a second. (Floods of unfinished handshakes: test_cluster_flood. The
# same attacks 10,000 times each are a measurement: docs/cluster.md.)
here=$(cd "$(dirname "$0")" && pwd)
. "$here/cluster_lib.sh"
stranger=$build/cluster_stranger
attempts=${STRANGER_ATTEMPTS:-150}

CLUSTER_SECURITY=curve make_config "$tmp/c.json" 3000 a b
"$build/cavelight-master" --config "$tmp/c.json" --keygen 2> "$tmp/keygen.log" || { cat "$tmp/keygen.log"; fail "keygen failed"; }
[ "$(stat -c %a "$tmp/c.keys/a.key")" = 600 ] || fail "a secret key is readable by others"
"$build/cavelight-master" --config "$tmp/c.json" --keygen 2> "$tmp/keygen2.log" && fail "keygen overwrote keys"
grep -q "remove the old keys" "$tmp/keygen2.log" || fail "keygen refusal unclear: $(cat "$tmp/keygen2.log")"

# run NAME FRAMES FPS [attack...]: a session of nodes a and b, attacks while it runs. FRAMES
# 0: until the attacks are over, then SIGTERM (however long STRANGER_ATTEMPTS makes them).
run() {
  local name=$1 frames=$2 fps=$3; shift 3
  rm -f "$tmp/ep"
  "$build/cavelight-master" --config "$tmp/c.json" --bind 'tcp://127.0.0.1:*' --endpoint-file "$tmp/ep" \
    --frames $frames --fps $fps --report "$tmp/$name.json" 2> "$tmp/$name-master.log" &
  local master=$!; pids+=($master)
  wait_for_file "$tmp/ep" 20
  local ep; ep=$(cat "$tmp/ep")
  for n in a b; do
    "$build/cavelight-node" --cluster "$tmp/c.json" --name $n --master "$ep" --render none --exit-with-master \
      2> "$tmp/$name-node-$n.log" &
    pids+=($!)
  done
  for _ in $(seq 200); do grep -q "running" "$tmp/$name-master.log" && break; sleep 0.1; done
  for attack in "$@"; do
    for key in none wrong stolen insider; do
      "$stranger" --config "$tmp/c.json" --endpoint "$ep" --attack $attack --key $key --victim a \
        --count $attempts --listen-ms 1500 >> "$tmp/$name-stranger.log" 2>&1 || fail "stranger $attack failed"
    done
  done
  if [ "$frames" = 0 ]; then
    kill -0 $master 2>/dev/null || { cat "$tmp/$name-master.log"; fail "run $name: the session ended during the attacks"; }
    kill -TERM $master
  fi
  wait $master || { cat "$tmp/$name-master.log"; fail "master of run $name failed"; }
}
run attacked 0 15 takeover read ready hello
cat "$tmp/attacked-stranger.log"
# The same number of frames without the stranger, as fast as the nodes go (--dt is fixed,
# so the parameters of each frame are the same): its checksums are what nothing changed means.
frames=$(json 'r["frames"]' "$tmp/attacked.json")
[ "$frames" -ge 10 ] || fail "only $frames frames ran during the attacks"
run quiet "$frames" 0
echo "$frames frames under attack"

for r in quiet attacked; do
  [ "$(json 'r["frames"]' "$tmp/$r.json")" = $frames ] || fail "$r: frames $(json 'r["frames"]' "$tmp/$r.json")"
  [ "$(json '(r["joins"], r["drops"], r["desyncs"], r["nodes_live_min"])' "$tmp/$r.json")" = "(2, 0, 0, 2)" ] \
    || { cat "$tmp/$r-master.log"; fail "$r: joins, drops, desyncs, live: $(json '(r["joins"], r["drops"], r["desyncs"], r["nodes_live_min"])' "$tmp/$r.json")"; }
done
want=$(json 'r["per_node"][0]["last_checksum"]' "$tmp/quiet.json")
[ "$(json '[n["last_checksum"] for n in r["per_node"]]' "$tmp/attacked.json")" = "['$want', '$want']" ] \
  || fail "parameters changed under attack: $(json '[n["last_checksum"] for n in r["per_node"]]' "$tmp/attacked.json") vs $want"
grep -q "replies=[1-9]\|received=[1-9]" "$tmp/attacked-stranger.log" && fail "the stranger got messages from the cluster"
[ "$(grep -c "attempts=$attempts " "$tmp/attacked-stranger.log")" = 16 ] || fail "not every attack ran"
[ "$(json 'r["refused_connections"] > 0' "$tmp/attacked.json")" = True ] || fail "no wrong key was refused"
lines=$(grep -c "refused\|unauthenticated" "$tmp/attacked-master.log" || true)
# Two kinds of line (refused keys, unknown peers): the first 5 each, then one per 10 s.
most=$(json 'int(2 * (5 + r["wall_seconds"] / 10 + 1))' "$tmp/attacked.json")
[ "$lines" -le "$most" ] || fail "$lines log lines for the stranger (at most $most): not rate-limited"
echo "stranger in the stream: $(json 'r["refused_connections"]' "$tmp/attacked.json") keys refused, $lines log lines, nothing changed"

# Replay: node b reaches the master through the stranger's relay, which records what b
# sends and sends the recording again on new connections while the session runs.
rm -f "$tmp/ep" "$tmp/rep"
"$build/cavelight-master" --config "$tmp/c.json" --bind 'tcp://127.0.0.1:*' --endpoint-file "$tmp/ep" \
  --frames $frames --fps 30 --report "$tmp/replayed.json" 2> "$tmp/replayed-master.log" &
master=$!; pids+=($master)
wait_for_file "$tmp/ep" 20
"$stranger" --config "$tmp/c.json" --endpoint "$(cat "$tmp/ep")" --attack replay --count $attempts \
  --endpoint-file "$tmp/rep" --listen-ms 600000 > "$tmp/replay.log" 2>&1 &
relay=$!; pids+=($relay)
wait_for_file "$tmp/rep" 20
"$build/cavelight-node" --cluster "$tmp/c.json" --name a --master "$(cat "$tmp/ep")" --render none --exit-with-master \
  2> /dev/null &
pids+=($!)
"$build/cavelight-node" --cluster "$tmp/c.json" --name b --master "$(cat "$tmp/rep")" --render none --exit-with-master \
  2> "$tmp/replayed-b.log" &
pids+=($!)
wait $master || { cat "$tmp/replayed-master.log"; fail "master of the replayed run failed"; }
wait $relay || fail "the relay failed"
cat "$tmp/replay.log"
grep -q "attempts=$attempts .*received=[1-9]" "$tmp/replay.log" || fail "nothing was replayed"
[ "$(json '(r["joins"], r["drops"], r["desyncs"], r["nodes_live_min"])' "$tmp/replayed.json")" = "(2, 0, 0, 2)" ] \
  || { cat "$tmp/replayed-master.log"; fail "replayed: joins, drops, desyncs, live: $(json '(r["joins"], r["drops"], r["desyncs"], r["nodes_live_min"])' "$tmp/replayed.json")"; }
[ "$(json '[n["last_checksum"] for n in r["per_node"]]' "$tmp/replayed.json")" = "['$want', '$want']" ] \
  || fail "parameters changed by the replays"
[ "$(json "r['handshakes_failed'] >= $attempts" "$tmp/replayed.json")" = True ] \
  || fail "only $(json 'r["handshakes_failed"]' "$tmp/replayed.json") of $attempts replays failed their handshake"
echo "replay of node b's captured traffic, $attempts times: every handshake failed, nothing changed"

# A fake master (its own key, or none) where the nodes look for theirs: they never take its
# parameters, and join the real master once it binds the same endpoint.
for key in wrong none; do
  rm -f "$tmp/fep"
  "$stranger" --config "$tmp/c.json" --endpoint 'tcp://127.0.0.1:*' --endpoint-file "$tmp/fep" --attack master \
    --key $key --listen-ms 3000 > "$tmp/fake-$key.log" 2>&1 &
  fake=$!; pids+=($fake)
  wait_for_file "$tmp/fep" 20
  fep=$(cat "$tmp/fep")
  t0=$(date +%s%N)
  node_pids=()
  for n in a b; do
    "$build/cavelight-node" --cluster "$tmp/c.json" --name $n --master "$fep" --render none --exit-with-master \
      2> "$tmp/fake-$key-node-$n.log" &
    node_pids+=($!); pids+=($!)
  done
  for _ in $(seq 300); do grep -q "handshake with the master" "$tmp/fake-$key-node-a.log" && break; sleep 0.01; done
  said=$(( ($(date +%s%N) - t0) / 1000000 ))
  wait $fake
  grep -q "received=0" "$tmp/fake-$key.log" || fail "the fake master ($key) heard from a node: $(cat "$tmp/fake-$key.log")"
  grep -q "joined" "$tmp/fake-$key-node-a.log" && fail "node a joined the fake master ($key)"
  # The nodes say why the handshakes fail: another key than master.pub, or no CURVE (a
  # connection closed before the master's greeting was read names both).
  cause="master.pub is not this master's key"
  [ $key = none ] && cause="the master uses another security mode"
  grep -q "handshake with the master at $fep failed (.*): .*$cause" "$tmp/fake-$key-node-a.log" \
    || { cat "$tmp/fake-$key-node-a.log"; fail "node a does not say why the fake master ($key) failed"; }
  "$build/cavelight-master" --config "$tmp/c.json" --bind "$fep" --frames $frames --fps 0 \
    --report "$tmp/after-$key.json" 2> "$tmp/after-$key.log" || { cat "$tmp/after-$key.log"; fail "real master failed"; }
  [ "$(json '[n["last_checksum"] for n in r["per_node"]]' "$tmp/after-$key.json")" = "['$want', '$want']" ] \
    || { cat "$tmp/after-$key.log"; fail "after the fake master ($key): $(json '[n["last_checksum"] for n in r["per_node"]]' "$tmp/after-$key.json") vs $want"; }
  # One join each, before the first frame: a late or repeated HELLO would reset every node's
  # LPV history mid-session (the checksum above shows it too, less clearly).
  [ "$(json '(r["joins"], r["nodes_live_min"])' "$tmp/after-$key.json")" = "(2, 2)" ] \
    || { cat "$tmp/after-$key.log"; fail "after the fake master ($key): joins, live: $(json '(r["joins"], r["nodes_live_min"])' "$tmp/after-$key.json")"; }
  for p in "${node_pids[@]}"; do wait $p || fail "a node failed after the fake master ($key)"; done
  echo "fake master ($key): node a said why its handshakes fail $said ms after it started; both joined the real master $(json 'round(r["nodes_wait_ms"])' "$tmp/after-$key.json") ms after it bound"
done
echo "fake master: no node took its parameters; the real master got both"

# Insecure mode trusts any master: hostile parameters are clamped and logged, never fatal.
make_config "$tmp/i.json" 3000 a
rm -f "$tmp/fep"
"$stranger" --config "$tmp/i.json" --endpoint 'tcp://127.0.0.1:*' --endpoint-file "$tmp/fep" --attack master \
  --key none --listen-ms 60000 > "$tmp/fake-i.log" 2>&1 &
fake=$!; pids+=($fake)
wait_for_file "$tmp/fep" 20
"$build/cavelight-node" --cluster "$tmp/i.json" --name a --master "$(cat "$tmp/fep")" --render none \
  2> "$tmp/fake-i-node.log" &
node=$!; pids+=($node)
# Until the node has rendered the fake master's frame (however loaded the machine is).
for _ in $(seq 600); do grep -q "out of range, clamped" "$tmp/fake-i-node.log" && break; sleep 0.1; done
kill $fake; wait $fake || true
kill -0 $node || { cat "$tmp/fake-i-node.log"; fail "the node exited on hostile parameters"; }
grep -q "out of range, clamped" "$tmp/fake-i-node.log" || { cat "$tmp/fake-i-node.log"; fail "no clamp logged"; }
grep -q 'security "insecure"' "$tmp/fake-i-node.log" || fail "insecure mode not named in the node's log"
echo "insecure mode: hostile parameters clamped, the node stays up"

# Insecure mode believes any name: one message under node a's name takes its routing id
# over on the master's side, and node a hears nothing more. With the default master_ms
# (400) it calls the master lost and reconnects on a fresh connection: back within a second.
MASTER_MS= make_config "$tmp/cut.json" 3000 a b
rm -f "$tmp/ep"
"$build/cavelight-master" --config "$tmp/cut.json" --bind 'tcp://127.0.0.1:*' --endpoint-file "$tmp/ep" --frames 0 \
  --fps 30 --report "$tmp/cut.json.r" 2> "$tmp/cut-master.log" &
master=$!; pids+=($master)
wait_for_file "$tmp/ep" 20
for n in a b; do
  "$build/cavelight-node" --cluster "$tmp/cut.json" --name $n --master "$(cat "$tmp/ep")" --render none 2> "$tmp/cut-$n.log" &
  pids+=($!)
done
for _ in $(seq 200); do grep -q "running" "$tmp/cut-master.log" && break; sleep 0.1; done
"$stranger" --config "$tmp/cut.json" --endpoint "$(cat "$tmp/ep")" --attack ready --key none --victim a --count 1 \
  --listen-ms 100 > /dev/null 2>&1
for _ in $(seq 100); do grep -q "reconnected to the master" "$tmp/cut-a.log" && break; sleep 0.05; done
sleep 0.3
kill -TERM $master; wait $master || true
grep -q "master lost: nothing heard for 400 ms" "$tmp/cut-a.log" && grep -q "reconnected to the master" "$tmp/cut-a.log" \
  || { cat "$tmp/cut-a.log" "$tmp/cut-master.log"; fail "node a did not come back after a stranger cut it off"; }
back=$(( 400 + $(grep -o "reconnected to the master at version [0-9]*, [0-9]* ms" "$tmp/cut-a.log" | head -1 | grep -o "[0-9]* ms" | grep -o "[0-9]*") ))
echo "insecure mode: node a cut off by a stranger's message under its name, back after $back ms (400 of them master_ms)"
[ "$back" -lt 1000 ] || fail "node a took $back ms to come back"

# Insecure mode believes any name, so every HELLO is a join or a refusal: the master's
# lines about a node are rate-limited (common/base/ratelog.h) however many arrive.
make_config "$tmp/f.json" 3000 a
rm -f "$tmp/ep"
"$build/cavelight-master" --config "$tmp/f.json" --bind 'tcp://127.0.0.1:*' --endpoint-file "$tmp/ep" \
  --frames 0 2> "$tmp/flood-master.log" &
master=$!; pids+=($master)
wait_for_file "$tmp/ep" 20
flood_start=$SECONDS
"$stranger" --config "$tmp/f.json" --endpoint "$(cat "$tmp/ep")" --attack badhello --key none --victim a \
  --count $attempts > "$tmp/flood.log" 2>&1 || fail "stranger badhello failed"
kill -TERM $master; wait $master || true
refusals=$(grep -c "another cluster config" "$tmp/flood-master.log" || true)
most=$(( 5 + (SECONDS - flood_start) / 10 + 1 ))  # the first 5, then one per 10 s
[ "$refusals" -ge 1 ] && [ "$refusals" -le $most ] || { cat "$tmp/flood-master.log"; fail "$refusals refusal lines for $attempts bad HELLOs (at most $most)"; }
echo "insecure mode: $attempts HELLOs with another config hash gave $refusals log lines"

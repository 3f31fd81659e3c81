#!/usr/bin/env bash
# Multi-host: master and nodes in two network namespaces joined by a veth pair, so the
# traffic crosses a (virtual) link between two hosts with their own addresses. Needs
# root (or CAP_NET_ADMIN) and iproute2; skipped with a message (exit 77) otherwise.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/cluster_lib.sh"

ns_m=cvm$$ ns_n=cvn$$
if ! command -v ip >/dev/null || ! ip netns add "$ns_m" 2>/dev/null; then
  echo "SKIP: cannot create network namespaces here (needs root and iproute2)"
  exit 77
fi
netns_cleanup() { ip netns del "$ns_m" 2>/dev/null || true; ip netns del "$ns_n" 2>/dev/null || true; cleanup; }
trap netns_cleanup EXIT
ip netns add "$ns_n"
ip link add "vm$$" type veth peer name "vn$$"
ip link set "vm$$" netns "$ns_m"
ip link set "vn$$" netns "$ns_n"
ip -n "$ns_m" addr add 10.77.0.1/24 dev "vm$$"
ip -n "$ns_n" addr add 10.77.0.2/24 dev "vn$$"
for ns in "$ns_m" "$ns_n"; do ip -n "$ns" link set lo up; done
ip -n "$ns_m" link set "vm$$" up
ip -n "$ns_n" link set "vn$$" up

make_config "$tmp/c.json" 3000 a b
sed -i 's#"bind": "tcp://127.0.0.1:1", "connect": "tcp://127.0.0.1:1"#"bind": "tcp://10.77.0.1:5599", "connect": "tcp://10.77.0.1:5599"#' "$tmp/c.json"
run() { # FRAMES REPORT
  ip netns exec "$ns_m" "$build/cavelight-master" --config "$tmp/c.json" --insecure-anywhere --frames "$1" --wait-ms 10000 \
    --report "$2" --quiet 2> "$tmp/master.log" &
  local m=$!
  pids+=($m)
  for n in a b; do
    ip netns exec "$ns_n" "$build/cavelight-node" --cluster "$tmp/c.json" --name $n --render none \
      --exit-with-master --quiet &
    pids+=($!)
  done
  wait $m || { cat "$tmp/master.log"; fail "master in namespace failed"; }
}
run 100 "$tmp/r.json"
[ "$(json 'r["frames"]' "$tmp/r.json")" = 100 ] || fail "not 100 frames across the veth link"
[ "$(json 'r["nodes_live_min"]' "$tmp/r.json")" = 2 ] || fail "a node missed frames across the link"
[ "$(json 'r["desyncs"]' "$tmp/r.json")" = 0 ] || fail "desync across the link"
echo "2 nodes in another namespace: round trip median $(json 'r["round_trip_ms"]["median"]' "$tmp/r.json") ms"

# With 5 ms of delay on the link each way, a frame's round trip must take at least 10 ms:
# the messages really cross it.
if ip netns exec "$ns_n" tc qdisc add dev "vn$$" root netem delay 5ms 2>/dev/null; then
  run 20 "$tmp/r2.json"
  [ "$(json 'r["round_trip_ms"]["median"] >= 10' "$tmp/r2.json")" = True ] || fail "delay on the link not seen"
  echo "with 5 ms link delay: round trip median $(json 'r["round_trip_ms"]["median"]' "$tmp/r2.json") ms"
else
  echo "note: tc netem unavailable, delay check skipped"
fi

#!/usr/bin/env bash
# A master that closes a node's CURVE handshakes for a while (as one shedding connections
# under a flood does: conn_guard.h) and then lets it in: the node says the close has two
# possible causes and does not blame its master.pub (issue 34: "most likely ... is not this
# master's key", false under a reconnect flood); the real master then takes it. A master
# that closes them for longer than the node's evidence time is named as a key mismatch by
# test_cluster_keys.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/cluster_lib.sh"

CLUSTER_SECURITY=curve make_config "$tmp/c.json" 3000 a
cd "$tmp"
"$build/cavelight-master" --config c.json --keygen 2> keygen.log || { cat keygen.log; fail "keygen failed"; }
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
ep="tcp://127.0.0.1:$port"

# The shedder: reads the start of each greeting and closes the connection, for 2.5 s.
python3 - "$port" > shed.log 2>&1 <<'PY' &
import socket, sys, time
s = socket.socket(); s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
s.bind(("127.0.0.1", int(sys.argv[1]))); s.listen(64); s.settimeout(0.1)
end, closed = time.time() + 2.5, 0
while time.time() < end:
    try:
        c, _ = s.accept()
    except socket.timeout:
        continue
    c.settimeout(0.5)
    try:
        c.recv(64)
    except OSError:
        pass
    c.close(); closed += 1
s.close(); print("closed", closed)
PY
shed=$!; pids+=($shed)
sleep 0.2
"$build/cavelight-node" --cluster c.json --name a --master "$ep" --render none 2> a.log &
pids+=($!)
wait $shed
grep -q "closed [1-9]" shed.log || fail "the shedder closed nothing: $(cat shed.log)"
"$build/cavelight-master" --config c.json --bind "$ep" --frames 0 --fps 30 2> master.log &
master=$!; pids+=($master)
for _ in $(seq 200); do grep -q "joined the master" a.log && break; sleep 0.05; done
cat a.log
grep -q "joined the master" a.log || { cat master.log; fail "node a did not join the master after the shedding"; }
grep -q "the master closed the connection in the CURVE handshake ([0-9]* in a row): a master shedding connections" a.log \
  || fail "node a does not say a closed handshake may be a shedding master"
grep -q "most likely" a.log && fail "node a blamed its master.pub while the master shed its connections"
echo "$(cat shed.log) handshakes in 2.5 s: the node named both causes, blamed no key, and joined"

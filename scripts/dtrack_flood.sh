#!/usr/bin/env bash
# dtrack_flood.sh BUILD_DIR [COUNT]: a master with a DTrack input on a loopback UDP port and
# one node (no rendering); COUNT datagrams (default 100000) arrive at the master's real
# socket: valid frames with a moving head, every seed of tests/fuzz/dtrack, truncations and
# random bytes. Prints the master's resident memory before and after, and whether the
# session went on. A measurement (docs/cluster.md), not a test.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
. "$root/tests/integration/cluster_lib.sh" "${1:?usage: $0 BUILD_DIR [COUNT]}"
count=${2:-100000}
port=$(python3 -c 'import socket; s=socket.socket(socket.AF_INET, socket.SOCK_DGRAM); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
cat > "$tmp/input.json" <<JSON
{"sources": [{"type": "dtrack", "name": "art", "port": $port, "bind": "127.0.0.1", "sender": "127.0.0.1", "head": 0}]}
JSON
make_config "$tmp/c.json" 3000 a
"$build/cavelight-master" --config "$tmp/c.json" --bind 'tcp://127.0.0.1:*' --endpoint-file "$tmp/ep" \
  --input "$tmp/input.json" --frames 0 --fps 60 --report "$tmp/r.json" 2> "$tmp/master.log" &
master=$!; pids+=($master)
wait_for_file "$tmp/ep" 20
"$build/cavelight-node" --cluster "$tmp/c.json" --name a --master "$(cat "$tmp/ep")" --render none \
  --exit-with-master 2> "$tmp/node.log" &
pids+=($!)
for _ in $(seq 200); do grep -q "running" "$tmp/master.log" && break; sleep 0.1; done
rss() { awk '/^VmRSS/ {print $2}' "/proc/$master/status"; }
sleep 1
before=$(rss)
python3 - "$port" "$count" "$root/tests/fuzz/dtrack" <<'PY'
import glob, math, os, random, socket, sys, time
port, count, seeds = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
corpus = [open(f, "rb").read() for f in sorted(glob.glob(seeds + "/*"))]
rng = random.Random(1)
s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
kinds = {"valid": 0, "seed": 0, "truncated": 0, "random": 0}
for i in range(count):
    k = i % 4
    if k == 0:
        x = 300 * math.sin(i * 1e-3)
        d = b"fr %d\n6d 1 [0 1.000][%.3f 1700.0 0.0][1 0 0 0 1 0 0 0 1]\n" % (i, x)
        kinds["valid"] += 1
    elif k == 1:
        d = corpus[i % len(corpus)]
        kinds["seed"] += 1
    elif k == 2:
        c = corpus[i % len(corpus)]
        d = c[: rng.randrange(len(c) + 1)]
        kinds["truncated"] += 1
    else:
        d = os.urandom(rng.randrange(1, 1400))
        kinds["random"] += 1
    s.sendto(d, ("127.0.0.1", port))
    if i % 200 == 199:
        time.sleep(0.002)  # about 60,000 a second: the socket buffer, not the sender, sets the loss
print("sent", count, "datagrams:", ", ".join("%d %s" % (v, k) for k, v in kinds.items()))
PY
sleep 1
after=$(rss)
kill -0 $master || { cat "$tmp/master.log"; fail "the master died"; }
kill -TERM $master; wait $master || true
echo "master RSS: $before kB before, $after kB after $count DTrack datagrams; frames $(json 'r["frames"]' "$tmp/r.json"), drops $(json 'r["drops"]' "$tmp/r.json")"
grep -c "" "$tmp/master.log" | xargs echo "master log lines:"

#!/usr/bin/env bash
# Curve keys: --keygen writes one bundle per host with exactly what that host needs and
# says where each goes; a node given only its bundle joins; at start the master and the
# nodes check every key pair they hold (two nodes' secret keys swapped, a garbage secret
# key) and name the file in one line, and a missing file is named with what to do on that
# host (not a keygen there); a node whose handshakes with the master fail says so,
# rate-limited, with the likely cause: its key unknown to the master, or a master.pub that
# is not this master's (named so once every handshake was closed for 6 s: a master shedding
# connections under a flood closes them too, test_cluster_handshake_shed). KEYS_FAIL_S
# (default 7) is how long those two nodes try (a measurement: docs/cluster.md).
here=$(cd "$(dirname "$0")" && pwd)
. "$here/cluster_lib.sh"

CLUSTER_SECURITY=curve make_config "$tmp/c.json" 3000 a b c
python3 - "$tmp/c.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c["nodes"][0]["host"] = c["nodes"][1]["host"] = "render1"
c["nodes"][2].update({"host": "render2", "workdir": "/srv/wall", "config": "cave.json"})
json.dump(c, open(sys.argv[1], "w"))
PY
cd "$tmp"
"$build/cavelight-master" --config c.json --keygen 2> keygen.log || { cat keygen.log; fail "keygen failed"; }
cat keygen.log
[ "$(cd c.keys/hosts/render1 && ls | tr '\n' ' ')" = "a.key a.pub b.key b.pub master.pub " ] || fail "render1's bundle: $(ls c.keys/hosts/render1)"
[ "$(cd c.keys/hosts/render2 && ls | tr '\n' ' ')" = "c.key c.pub master.pub " ] || fail "render2's bundle: $(ls c.keys/hosts/render2)"
[ "$(stat -c %a c.keys/hosts/render1/a.key c.keys/hosts/render2 c.keys/a.key | tr '\n' ' ')" = "600 700 600 " ] \
  || fail "bundle permissions"
cmp -s c.keys/a.key c.keys/hosts/render1/a.key && cmp -s c.keys/master.pub c.keys/hosts/render2/master.pub || fail "bundles differ from the keys"
grep -q "render1 (nodes a, b): c.keys/hosts/render1/{a.key, a.pub, b.key, b.pub, master.pub} -> render1:$tmp/c.keys/" keygen.log \
  && grep -q "render2 (node c): c.keys/hosts/render2/{c.key, c.pub, master.pub} -> render2:/srv/wall/c.keys/" keygen.log \
  || fail "keygen does not say which bundle goes where"
"$build/cavelight-master" --config c.json --keygen 2> again.log && fail "keygen overwrote keys"
grep -q "remove the old keys" again.log || fail "keygen refusal unclear: $(cat again.log)"
echo "keygen: one bundle per host, each named with its destination"

rm -f ep
"$build/cavelight-master" --config c.json --bind 'tcp://127.0.0.1:*' --endpoint-file ep --frames 0 --fps 30 \
  --report r.json 2> master.log &
master=$!; pids+=($master)
wait_for_file ep 20
ep=$(cat ep)

# A node host given only its bundle, at the key folder its config names, joins.
mkdir -p host-a && cp c.json host-a/ && cp -r c.keys/hosts/render1 host-a/c.keys
(cd host-a && exec "$build/cavelight-node" --cluster c.json --name a --master "$ep" --render none 2> ../a.log) &
pids+=($!)
for _ in $(seq 100); do grep -q "joined the master" a.log && break; sleep 0.1; done
grep -q "joined the master" a.log || { cat a.log master.log; fail "node a did not join with its bundle"; }
echo "node a joined with nothing but its host's bundle"

# Handshakes that fail: node b with a key pair of another keygen (unknown to the master),
# node c with another keygen's master.pub. Each says why, rate-limited.
mkdir -p other && cp c.json other/ && "$build/cavelight-master" --config other/c.json --keygen 2> /dev/null
mkdir -p host-b/c.keys host-c/c.keys && cp c.json host-b/ && cp c.json host-c/
cp other/c.keys/b.key other/c.keys/b.pub c.keys/master.pub host-b/c.keys/
cp c.keys/c.key c.keys/c.pub other/c.keys/master.pub host-c/c.keys/
t0=$(date +%s%N)
for n in b c; do
  (cd host-$n && exec "$build/cavelight-node" --cluster c.json --name $n --master "$ep" --render none 2> ../$n.log) &
  pids+=($!)
done
start=$SECONDS
for _ in $(seq 1000); do grep -q "handshake with the master" b.log && grep -q "handshake with the master" c.log && break; sleep 0.01; done
said=$(( ($(date +%s%N) - t0) / 1000000 ))
sleep ${KEYS_FAIL_S:-7}
kill -TERM $master; wait $master || true
cat b.log c.log
grep -q "handshake with the master at $ep failed (.*): the master refused this node's key (status 400): c.keys/b.pub is not the key the master has for node b" b.log \
  || fail "node b with an unknown key does not say so"
grep -q "handshake with the master at $ep failed (.*): the master closed the connection in the CURVE handshake: most likely c.keys/master.pub is not this master's key" c.log \
  || fail "node c with another master.pub does not say so"
most=$(( 5 + (SECONDS - start) / 10 + 1 ))
for n in b c; do
  lines=$(grep -c "handshake with the master" $n.log)
  [ "$lines" -le $most ] || fail "node $n: $lines handshake lines (at most $most)"
done
[ "$(json 'r["refused_connections"] > 0 and r["joins"] == 1' r.json)" = True ] || fail "report: $(json '(r["refused_connections"], r["joins"])' r.json)"
for n in b c; do
  echo "node $n: $(grep -c "handshake with the master" $n.log) lines for $(tail -1 $n.log | grep -o '[0-9]* so far, [0-9]* not logged') in $(( SECONDS - start )) s"
done
echo "failed handshakes: both nodes said why within $said ms of starting (unknown key; not this master's master.pub), rate-limited"

# Key checks at start. Two nodes' secret keys swapped in the master's folder: the master
# names the pair. A node's swapped pair, a garbage secret key: the node names its file.
cp -r c.keys swapped.keys && mv swapped.keys/a.key x.key && mv swapped.keys/b.key swapped.keys/a.key && mv x.key swapped.keys/b.key
python3 - c.json swapped.json <<'PY'
import json, sys
c = json.load(open(sys.argv[1])); c["security"]["keys"] = "swapped.keys"; json.dump(c, open(sys.argv[2], "w"))
PY
expect_one_line() { # LOG PATTERN WHAT
  [ "$(wc -l < "$1")" = 1 ] && grep -q "$2" "$1" || { cat "$1"; fail "$3"; }
}
"$build/cavelight-master" --config swapped.json --bind 'tcp://127.0.0.1:*' --frames 1 --wait-ms 100 2> m-swap.log \
  && fail "the master started with two nodes' keys swapped"
expect_one_line m-swap.log "swapped.keys/a.key: this secret key's public key is not the one in swapped.keys/a.pub" \
  "the master does not name the swapped pair"
"$build/cavelight-node" --cluster swapped.json --name b --render none 2> n-swap.log && fail "node b started with a.key"
expect_one_line n-swap.log "swapped.keys/b.key: this secret key's public key is not the one in swapped.keys/b.pub" \
  "node b does not name its swapped pair"
cp host-a/c.keys/a.pub host-a/a.pub.good
printf '%s\n' "$(head -c 40 /dev/zero | tr '\0' 'x')" > host-a/c.keys/a.key
(cd host-a && "$build/cavelight-node" --cluster c.json --name a --render none 2> ../n-garbage.log) && fail "node a started with a garbage key"
expect_one_line n-garbage.log "c.keys/a.key: this secret key's public key is not the one in c.keys/a.pub" \
  "node a does not name its garbage secret key"
rm host-a/c.keys/a.pub
(cd host-a && "$build/cavelight-node" --cluster c.json --name a --render none 2> ../n-missing.log) && fail "node a started without a.pub"
expect_one_line n-missing.log "c.keys/a.pub: No such file or directory: node a needs a.key, a.pub and master.pub in c.keys (security.keys of c.json): copy them from c.keys/hosts/render1 on the master's host" \
  "a missing file is not named with what to do on the node's host"
echo "key checks at start: swapped pairs, a garbage secret key and a missing file named in one line each"

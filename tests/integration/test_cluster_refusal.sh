#!/usr/bin/env bash
# Scenes and parameters a node cannot take: the master checks a scene's parameters as the
# nodes do before it starts any (a glTF of finite but huge vertices made a light of
# infinite power, every node refused every snapshot, and the master reported 5 frames and
# exit 0); a node that cannot load the scene tells the master why (REFUSE), the master
# prints the node's reason and ends non-zero, for a spawned node and for one started by
# hand elsewhere; a node sent a value it cannot take refuses it and tells its master why.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/cluster_lib.sh"

# A triangle 2e38 m wide: finite vertices, no light (the added light's power would overflow).
python3 - "$tmp/huge.gltf" <<'PY'
import base64, json, struct, sys
v = [-1e38, 0, -1e38, 1e38, 0, -1e38, 0, 1e38, 1e38]
b = struct.pack("<9f", *v)
json.dump({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
           "buffers": [{"byteLength": len(b), "uri": "data:application/octet-stream;base64," + base64.b64encode(b).decode()}],
           "bufferViews": [{"buffer": 0, "byteLength": len(b)}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                          "min": [-1e38, 0, -1e38], "max": [1e38, 1e38, 1e38]}]}, open(sys.argv[1], "w"))
PY
make_config "$tmp/c.json" 5000 a b
set +e
"$build/cavelight-master" --config "$tmp/c.json" --bind 'tcp://127.0.0.1:*' --spawn-local --scene "$tmp/huge.gltf" \
  --frames 5 --quiet --out "$tmp/huge" 2> "$tmp/huge.log"
rc=$?
set -e
# Such a scene is beyond the scenes' extent limit (docs/node.md), which the master applies
# as it loads the scene, as every node would.
[ $rc = 1 ] && [ "$(wc -l < "$tmp/huge.log")" = 1 ] \
  && grep -q "scene $tmp/huge.gltf: scene triangle 0 has a vertex at .*beyond the limit of 100000 m" "$tmp/huge.log" \
  || { cat "$tmp/huge.log"; fail "the master took a scene no node can take (exit $rc)"; }
[ -e "$tmp/huge/logs" ] && fail "nodes were started for a scene the master refused"
echo "a scene of 1e38 m: refused by the master before any node starts"

# Node b's working folder lacks the scene (a relative path): it says why, the master says
# so in its own words, the session runs with node a and ends with exit 1.
mkdir -p "$tmp/work" "$tmp/elsewhere"
cp "$here/../../scenes/room.gltf" "$tmp/work/"
python3 - "$tmp/c.json" "$tmp/work/c.json" "$tmp/elsewhere" <<'PY'
import json, sys
c = json.load(open(sys.argv[1])); c["nodes"][1]["workdir"] = sys.argv[3]; json.dump(c, open(sys.argv[2], "w"))
PY
cd "$tmp/work"
set +e
"$build/cavelight-master" --config c.json --bind 'tcp://127.0.0.1:*' --spawn-local --scene room.gltf --frames 5 \
  --quiet --report r.json --out out --node-args "$small_render" 2> spawn.log
rc=$?
set -e
[ $rc = 1 ] || { cat spawn.log; fail "a session with a node that refused the scene ended with $rc"; }
grep -q "^cavelight-master: node b refused the scene: scene room.gltf: cannot" spawn.log \
  && grep -q "^cavelight-master: node b refused the scene (1 refusals), the last: scene room.gltf" spawn.log \
  || { cat spawn.log; fail "the master does not give node b's reason"; }
[ "$(json '(r["frames"], r["per_node"][0]["frames_ready"], r["refusals"], r["per_node"][1]["refusals"])' r.json)" = "(5, 5, 1, 1)" ] \
  && json 'r["per_node"][1]["last_refusal"]' r.json | grep -q "^scene room.gltf: cannot" \
  || fail "report: $(json '(r["frames"], r["per_node"][0]["frames_ready"], r["refusals"], r["per_node"][1])' r.json)"
echo "spawned node without the scene: its reason in the master's output, exit 1, node a rendered every frame"

# The same with the nodes started by hand, node b in a folder without the scene: only its
# REFUSE can tell the master (nothing of node b's output reaches the master's).
rm -f ep
"$build/cavelight-master" --config c.json --bind 'tcp://127.0.0.1:*' --endpoint-file ep --scene room.gltf \
  --frames 5 --wait-ms 5000 --report r2.json 2> hand.log &
master=$!; pids+=($master)
wait_for_file ep 20
"$build/cavelight-node" --cluster c.json --name a --master "$(cat ep)" --scene room.gltf $small_render \
  --exit-with-master 2> a.log &
pids+=($!)
(cd "$tmp/elsewhere" && exec "$build/cavelight-node" --cluster "$tmp/work/c.json" --name b --master "$(cat "$tmp/work/ep")" \
  --scene room.gltf $small_render 2> "$tmp/work/b.log") && fail "node b started without its scene"
set +e
wait $master
rc=$?
set -e
[ $rc = 1 ] && grep -q "node b refused the scene: scene room.gltf: cannot" hand.log \
  || { cat hand.log b.log; fail "a node started by hand: its reason is not in the master's output (exit $rc)"; }
echo "node started by hand without the scene: its reason in the master's output, exit 1"

# A master that sends a value no node can take (an infinite light; here a fake master, the
# real one refuses such a scene): the node refuses it, says why to its master, stays up.
rm -f fep
"$build/cluster_stranger" --config c.json --endpoint 'tcp://127.0.0.1:*' --endpoint-file fep --attack master \
  --key none --nonfinite 1 --listen-ms 4000 > fake.log 2>&1 &
fake=$!; pids+=($fake)
wait_for_file fep 20
"$build/cavelight-node" --cluster c.json --name a --master "$(cat fep)" --render none 2> nf.log &
node=$!; pids+=($node)
wait $fake || fail "the fake master failed"
kill -0 $node || fail "the node exited on a value it cannot take"
grep -q 'refusals=[1-9][0-9]* why="snapshot [0-9]*: invalid values' fake.log \
  || { cat fake.log nf.log; fail "the node did not tell its master why it refused"; }
echo "a node sent an infinite value: refused, its master told why ($(grep -o 'refusals=[0-9]*' fake.log))"

#!/usr/bin/env bash
# Hostile input files, as the outside check of issue 34 made them, each refused in one line
# naming the file and the limit, with a non-zero exit, by the node and by the master's
# --check: a glTF with huge positions (1e20: a heap overflow in the caches' placement; 1e10:
# a hang; a caches cluster of 2 reported only "0 of 2 nodes joined"), a glTF and a cluster config of 200,000 nested arrays (a stack overflow in the
# JSON parsers), and a FIFO named as a screen's MPCDI file or as the scene (a blocking open).
here=$(cd "$(dirname "$0")" && pwd)
. "$here/cluster_lib.sh"
node=$build/cavelight-node
master=$build/cavelight-master

python3 - "$tmp" <<'PY'
import base64, json, struct, sys
out = sys.argv[1]
def gltf(name, s):
    # a quad of side s on the floor and a point light above it
    pos = [0, 0, 0, s, 0, 0, s, 0, s, 0, 0, 0, s, 0, s, 0, 0, s]
    data = struct.pack('<18f', *pos)
    g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
         "nodes": [{"mesh": 0}, {"translation": [1, 2, 1], "extensions": {"KHR_lights_punctual": {"light": 0}}}],
         "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 10}]}},
         "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
         "accessors": [{"bufferView": 0, "componentType": 5126, "count": 6, "type": "VEC3",
                        "min": [0, 0, 0], "max": [s, 0, s]}],
         "bufferViews": [{"buffer": 0, "byteLength": len(data)}],
         "buffers": [{"byteLength": len(data),
                      "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}]}
    json.dump(g, open(out + "/" + name, "w"))
gltf("huge20.gltf", 1e20)
gltf("huge10.gltf", 1e10)
gltf("fine.gltf", 4)
open(out + "/nested.gltf", "w").write("[" * 200000 + "]" * 200000)
PY
make_config "$tmp/c.json" 3000 a
SETTINGS='"gi": "caches"' make_config "$tmp/c2.json" 3000 a b

refused() { # WHAT PATTERN COMMAND...
  local what=$1 pattern=$2 rc=0; shift 2
  timeout 60 "$@" > "$tmp/out.log" 2>&1 || rc=$?
  [ $rc != 0 ] && [ $rc != 124 ] && [ $rc -lt 128 ] || { cat "$tmp/out.log"; fail "$what: exit $rc"; }
  grep -q -- "$pattern" "$tmp/out.log" || { cat "$tmp/out.log"; fail "$what: no line '$pattern'"; }
  echo "$what: exit $rc, '$(grep -- "$pattern" "$tmp/out.log" | head -1)'"
}

for s in 20 10; do
  refused "node, caches, positions 1e$s" "huge$s.gltf: scene triangle 0 has a vertex at 1e+$s m, beyond the limit of 100000 m" \
    "$node" --standalone --scene "$tmp/huge$s.gltf" --gi caches --frames 1 --width 64 --out "$tmp/o"
  refused "master --check, positions 1e$s" "huge$s.gltf: scene triangle 0 has a vertex at 1e+$s m, beyond the limit of 100000 m" \
    "$master" --config "$tmp/c.json" --scene "$tmp/huge$s.gltf" --check
done
refused "master session of 2 nodes, positions 1e20" "huge20.gltf: scene triangle 0 has a vertex at 1e+20 m, beyond the limit" \
  "$master" --config "$tmp/c2.json" --scene "$tmp/huge20.gltf" --bind 'tcp://127.0.0.1:*' --spawn-local --frames 1
refused "node, nested glTF" "nested.gltf: JSON nested deeper than 128 levels (at byte 128)" \
  "$node" --standalone --scene "$tmp/nested.gltf" --frames 1 --width 64 --out "$tmp/o"
refused "master --check, nested glTF" "nested.gltf: JSON nested deeper than 128 levels (at byte 128)" \
  "$master" --config "$tmp/c.json" --scene "$tmp/nested.gltf" --check
cp "$tmp/nested.gltf" "$tmp/nested.json"
refused "master, nested cluster config" "cluster config $tmp/nested.json: JSON nested deeper than 128 levels" \
  "$master" --config "$tmp/nested.json" --check

mkfifo "$tmp/wall.mpcdi" "$tmp/fifo.gltf"
python3 - "$tmp/c.json" "$tmp/fifo.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c["nodes"][0]["screens"] = [{"name": "front-l", "warp": {"mpcdi": "wall.mpcdi", "region": "p1"}}]
json.dump(c, open(sys.argv[2], "w"))
PY
refused "master --check, FIFO as the MPCDI file" "wall.mpcdi: not a regular file (a FIFO)" \
  "$master" --config "$tmp/fifo.json" --check
refused "node, FIFO as the MPCDI file" "wall.mpcdi: not a regular file (a FIFO)" \
  "$node" --cluster "$tmp/fifo.json" --name a
refused "node, FIFO as the scene" "fifo.gltf: cannot read it (not a regular file" \
  "$node" --standalone --scene "$tmp/fifo.gltf" --frames 1 --width 64 --out "$tmp/o"
"$node" --standalone --scene "$tmp/fine.gltf" --gi caches --frames 1 --width 64 --out "$tmp/o" 2> "$tmp/fine.log" \
  || { cat "$tmp/fine.log"; fail "the same glTF at 4 m did not render"; }
echo "the same glTF at 4 m renders"

#!/usr/bin/env bash
# glTF files as users export them, through cavelight-node --standalone: the file's first
# camera is the view (its aspect ratio sets the image height), --camera NAME|INDEX picks
# another and names the ones there are when it does not exist; a closed room without lights
# gets one light inside it and one warning; a view that receives no light says so once, not
# once per frame; the reference renders the same file from the same camera; buffers outside
# the file's folder are refused unless allowed; --scene-transform and the config's
# scene_transform place a model every node shows alike.
set -euo pipefail
build=$1
node="$build/cavelight-node"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# A closed 4 x 3 x 4 m room facing in, with a block; cameras, lights as asked.
python3 - "$out" <<'EOF'
import base64, json, struct, sys
out = sys.argv[1]
def box(lo, hi, inward):
    tris, nrms = [], []
    for axis in range(3):
        for side in (0, 1):
            u, v = (axis + 1) % 3, (axis + 2) % 3
            def corner(a, b):
                p = [0.0] * 3
                p[axis] = hi[axis] if side else lo[axis]
                p[u] = hi[u] if a else lo[u]
                p[v] = hi[v] if b else lo[v]
                return p
            c = [corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)]
            n = [0.0] * 3
            n[axis] = (1 if side else -1) * (-1 if inward else 1)
            for k in (0, 1, 2, 0, 2, 3):
                tris += c[k]
                nrms += n
    return tris, nrms
def write(name, lights=(), cameras=()):
    pos, nrm = box([-2, 0, -2], [2, 3, 2], True)
    p2, n2 = box([-0.9, 0, -0.6], [-0.1, 1, 0.2], False)
    pos += p2; nrm += n2
    data = struct.pack('<%df' % len(pos), *pos) + struct.pack('<%df' % len(nrm), *nrm)
    half = len(data) // 2
    g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
         "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}}]}],
         "accessors": [{"bufferView": i, "componentType": 5126, "count": len(pos) // 3, "type": "VEC3"} for i in (0, 1)],
         "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": half},
                         {"buffer": 0, "byteOffset": half, "byteLength": half}],
         "buffers": [{"byteLength": len(data),
                      "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}]}
    for light, translation in lights:
        g.setdefault("extensions", {"KHR_lights_punctual": {"lights": []}})
        ls = g["extensions"]["KHR_lights_punctual"]["lights"]
        g["nodes"].append({"translation": translation,
                           "extensions": {"KHR_lights_punctual": {"light": len(ls)}}})
        ls.append(light)
        g["scenes"][0]["nodes"].append(len(g["nodes"]) - 1)
    for node_name, cam_name, translation, rotation in cameras:
        g.setdefault("cameras", [])
        g["nodes"].append({"name": node_name, "translation": translation, "rotation": rotation,
                           "camera": len(g["cameras"])})
        g["cameras"].append({"name": cam_name, "type": "perspective",
                             "perspective": {"yfov": 1.0, "znear": 0.05, "aspectRatio": 2.0}})
        g["scenes"][0]["nodes"].append(len(g["nodes"]) - 1)
    json.dump(g, open("%s/%s" % (out, name), "w"))
lamp = ({"type": "point", "intensity": 8}, [0.4, 2.3, 0.3])
# CamNode looks along -z (identity rotation); TopNode looks straight down (-90 deg about x).
cams = [("CamNode", "Main", [0.5, 1.6, 1.8], [0, 0, 0, 1]),
        ("TopNode", "Top", [0.5, 2.8, 0.5], [-0.7071068, 0, 0, 0.7071068])]
write("cams.gltf", [lamp], cams)
write("dark.gltf")
write("off.gltf", [({"type": "point", "intensity": 0}, [0.4, 2.3, 0.3])], cams[:1])
# Every surface emissive, no light: the renderer adds none (an emitter lights it).
glow = json.load(open("%s/dark.gltf" % out))
glow["materials"] = [{"emissiveFactor": [1, 1, 1]}]
glow["meshes"][0]["primitives"][0]["material"] = 0
json.dump(glow, open("%s/glow.gltf" % out, "w"))

# A site exported Z up in centimetres, 100 m from its origin: a 10 x 10 m ground, a 1 m
# block, a lamp 3 m up; its buffer in site.bin, and a copy one folder down that reaches up
# for it.
ground = [10000, 5000, 0, 11000, 5000, 0, 11000, 6000, 0, 10000, 5000, 0, 11000, 6000, 0, 10000, 6000, 0]
block, _ = box([10450, 5200, 0], [10550, 5300, 100], False)
pos = ground + block
data = struct.pack('<%df' % len(pos), *pos)
open("%s/site.bin" % out, "wb").write(data)
site = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"mesh": 0}, {"translation": [10500, 5500, 300],
                                "extensions": {"KHR_lights_punctual": {"light": 0}}}],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 40000}]}},
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(pos) // 3, "type": "VEC3"}],
        "bufferViews": [{"buffer": 0, "byteLength": len(data)}],
        "buffers": [{"byteLength": len(data), "uri": "site.bin"}]}
json.dump(site, open("%s/site.gltf" % out, "w"))
site["buffers"][0]["uri"] = "../site.bin"
import os
os.mkdir("%s/sub" % out)
json.dump(site, open("%s/sub/site.gltf" % out, "w"))
EOF

small=(--width 64 --rsm 64 --lattice 8)
run() { # name args...: stdout and stderr of a standalone run kept as $out/name.{log,err}
    local name=$1; shift
    "$node" --standalone "${small[@]}" --out "$out/$name" "$@" > "$out/$name.log" 2> "$out/$name.err" \
        || { cat "$out/$name.err" >&2; fail "$name exited non-zero"; }
}

# The file's first camera, its aspect ratio 2 making 64 x 32 images.
run first --scene "$out/cams.gltf"
grep -q '"height":[[:space:]]*32' "$out/first/report.json" || fail "the camera's aspect ratio did not set the height"
run by_name --scene "$out/cams.gltf" --camera TopNode
run by_camera_name --scene "$out/cams.gltf" --camera Top
run by_index --scene "$out/cams.gltf" --camera 1
cmp -s "$out/by_name/frame0000_mono.png" "$out/by_index/frame0000_mono.png" || fail "--camera TopNode and --camera 1 differ"
cmp -s "$out/by_name/frame0000_mono.png" "$out/by_camera_name/frame0000_mono.png" || fail "--camera TopNode and --camera Top differ"
cmp -s "$out/first/frame0000_mono.png" "$out/by_index/frame0000_mono.png" && fail "--camera 1 shows the first camera's view"
run index0 --scene "$out/cams.gltf" --camera 0
cmp -s "$out/first/frame0000_mono.png" "$out/index0/frame0000_mono.png" || fail "--camera 0 is not the default view"
for f in first by_name; do
    grep -q "receives no light\|has no lights" "$out/$f.err" && { cat "$out/$f.err" >&2; fail "$f warned"; }
done

# An unknown camera: one line naming the cameras there are.
if "$node" --standalone --scene "$out/cams.gltf" --camera Nope > /dev/null 2> "$out/err"; then
    fail "--camera Nope succeeded"
fi
[ "$(wc -l < "$out/err")" -eq 1 ] || { cat "$out/err" >&2; fail "--camera Nope gave more than one line"; }
grep -q 'camera Nope: no such camera; the scene has 0 "CamNode", 1 "TopNode"' "$out/err" \
    || { cat "$out/err" >&2; fail "--camera Nope does not list the cameras"; }
if "$node" --standalone --scene "$out/dark.gltf" --camera 0 > /dev/null 2> "$out/err"; then
    fail "--camera on a scene without cameras succeeded"
fi
grep -q "has no cameras" "$out/err" || { cat "$out/err" >&2; fail "no 'has no cameras' line"; }

# A closed room without lights or camera: one warning, a light inside, a lit view inside.
run dark --scene "$out/dark.gltf" --frames 3
[ "$(grep -c "has no lights: added a point light" "$out/dark.err")" -eq 1 ] \
    || { cat "$out/dark.err" >&2; fail "not exactly one 'has no lights' warning"; }
grep -q "receives no light" "$out/dark.err" && { cat "$out/dark.err" >&2; fail "the room without lights renders black"; }

# Its only light at zero intensity: one warning over four frames, not one per frame.
run off --scene "$out/off.gltf" --frames 4
[ "$(grep -c "receives no light: every light is off" "$out/off.err")" -eq 1 ] \
    || { cat "$out/off.err" >&2; fail "not exactly one 'receives no light' warning in 4 frames"; }

# A camera outside the room, looking away from it: the view is black because nothing is
# in it, and says so (not that no light reaches it).
run away --scene "$out/cams.gltf" --position 0.5,1.6,40 --target 0.5,1.6,80 --frames 2
[ "$(grep -c "receives no light: nothing in view" "$out/away.err")" -eq 1 ] \
    || { cat "$out/away.err" >&2; fail "not exactly one 'nothing in view' warning"; }
grep -q "every light is off\|no light reaches" "$out/away.err" && { cat "$out/away.err" >&2; fail "away: wrong reason"; }
grep -q "nothing in view" "$out/off.err" && { cat "$out/off.err" >&2; fail "off: the room is in view"; }

# Emissive surfaces and no light: one line that says so.
run glow --scene "$out/glow.gltf" --frames 2
[ "$(grep -c "only emissive materials and no light" "$out/glow.err")" -eq 1 ] \
    || { cat "$out/glow.err" >&2; fail "not exactly one 'only emissive materials and no light' warning"; }

# The reference renders the same file from the same camera, lit.
"$node" --standalone --renderer reference --samples 2 --bounces 2 --width 64 \
    --scene "$out/cams.gltf" --out "$out/ref" > /dev/null 2> "$out/ref.err" || fail "reference failed"
grep -q '"height":[[:space:]]*32' "$out/ref/reference.json" || fail "the reference ignored the camera's aspect ratio"
grep -q '"lights":[[:space:]]*1' "$out/ref/reference.json" || fail "the reference has no light"
grep -q "receives no light" "$out/ref.err" && { cat "$out/ref.err" >&2; fail "the reference renders black"; }
"$node" --standalone --renderer reference --samples 1 --bounces 1 --width 32 \
    --scene "$out/off.gltf" --out "$out/ref_off" > /dev/null 2> "$out/ref_off.err" || fail "reference failed"
grep -q "receives no light" "$out/ref_off.err" || fail "the reference did not warn about a black view"

# A 2-node local cluster on the point-light file: the light's type travels in the parameter
# store, so both nodes render the same light (equal checksums, no desync). On the room
# without lights the master says so once; the nodes, which load the scene too, do not.
master="$build/cavelight-master"
cat > "$out/c2.json" <<'JSON'
{"name": "gltf", "master": {"bind": "tcp://127.0.0.1:1", "connect": "tcp://127.0.0.1:1"},
 "security": {"mode": "insecure"},
 "timeouts": {"barrier_ms": 20000, "heartbeat_ms": 100, "master_ms": 3000, "stall_min_ms": 20000},
 "observer": {"eye_separation": 0.064, "home": [0.5, 1.6, 1.0]},
 "screens": [
  {"name": "l", "bottom_left": [-1.5,0,-1.5], "bottom_right": [0,0,-1.5], "top_left": [-1.5,3,-1.5]},
  {"name": "r", "bottom_left": [0,0,-1.5], "bottom_right": [1.5,0,-1.5], "top_left": [0,3,-1.5]}],
 "nodes": [{"name": "a", "screens": ["l"], "resolution": [32, 32], "output": "headless"},
           {"name": "b", "screens": ["r"], "resolution": [32, 32], "output": "headless"}]}
JSON
for scene in cams dark; do
    "$master" --config "$out/c2.json" --bind 'tcp://127.0.0.1:*' --spawn-local --scene "$out/$scene.gltf" \
        --frames 4 --report "$out/$scene.json" --lattice 16 --rsm 64 --node-args "--threads 1" \
        --quiet 2> "$out/$scene-master.log" || { cat "$out/$scene-master.log" >&2; fail "cluster on $scene failed"; }
    python3 - "$out/$scene.json" <<'PY' || { cat "$out/$scene-master.log" >&2; fail "cluster on $scene: desync"; }
import json, sys
r = json.load(open(sys.argv[1]))
assert r["frames"] == 4 and r["desyncs"] == 0, r
assert len(set(n["last_checksum"] for n in r["per_node"])) == 1, r["per_node"]
PY
done
[ "$(grep -c "has no lights" "$out/cams-master.log")" -eq 0 ] || fail "the lit file got a 'has no lights' line"
[ "$(grep -c "has no lights: added a point light" "$out/dark-master.log")" -eq 1 ] \
    || { cat "$out/dark-master.log" >&2; fail "not exactly one 'has no lights' line from the cluster"; }

# Buffers only from the scene file's folder or below, unless allowed: one line naming the
# uri, never what is there.
if "$node" --standalone --scene "$out/sub/site.gltf" --width 32 > /dev/null 2> "$out/err"; then
    fail "a buffer outside the scene's folder was read"
fi
[ "$(wc -l < "$out/err")" -eq 1 ] && grep -q 'buffers\[0\].uri "../site.bin" is outside the scene file.s folder' "$out/err" \
    || { cat "$out/err" >&2; fail "no one-line refusal naming the uri"; }
run outside --scene "$out/sub/site.gltf" --allow-outside-paths

# Placement: as modelled the site is nowhere near the CAVE and the nodes say their views
# receive no light; placed by the master's --scene-transform (which the nodes it starts get
# too) or by the config's scene_transform, every view shows it lit, all nodes alike.
sed 's/"security"/"scene_transform": {"up": "z", "scale": 0.01}, "security"/' "$out/c2.json" > "$out/c2-placed.json"
for how in none option config; do
    cfg="$out/c2.json" args=()
    [ $how = option ] && args=(--scene-transform '{"up": "z", "scale": 0.01}')
    [ $how = config ] && cfg="$out/c2-placed.json"
    "$master" --config "$cfg" --bind 'tcp://127.0.0.1:*' --spawn-local --scene "$out/site.gltf" "${args[@]}" \
        --frames 2 --out "$out/site-$how" --report "$out/site-$how.json" \
        --lattice 16 --rsm 64 --node-args "--threads 1" 2> "$out/site-$how.log" \
        || { cat "$out/site-$how.log" >&2; fail "cluster on the site ($how) failed"; }
    python3 -c "import json,sys; r=json.load(open(sys.argv[1])); assert r['frames'] == 2 and r['desyncs'] == 0, r" \
        "$out/site-$how.json" || fail "site ($how): desync"
done
grep -q "receives no light" "$out/site-none.log" || { cat "$out/site-none.log" >&2; fail "the site as modelled lit the walls"; }
for how in option config; do
    grep -q "receives no light" "$out/site-$how.log" && { cat "$out/site-$how.log" >&2; fail "the placed site ($how) left a view dark"; }
done
# A bad transform is refused in one line naming the field, before any node starts.
if "$master" --config "$out/c2.json" --spawn-local --out "$out/bad" --scene-transform '{"up": "x"}' 2> "$out/err"; then
    fail "--scene-transform with up x was accepted"
fi
[ "$(wc -l < "$out/err")" -eq 1 ] && grep -q "scene_transform.up: must be one of: y, z" "$out/err" \
    || { cat "$out/err" >&2; fail "no one-line refusal naming scene_transform.up"; }
[ ! -e "$out/bad" ] || fail "nodes were started for a refused transform"
echo "glTF CLI: cameras, --camera, default light, the no-light warnings, outside paths, placement and 2-node clusters ok"

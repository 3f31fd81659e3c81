#!/usr/bin/env bash
# Two overlapping projectors of one wall, blended by an MPCDI file:
#   - configs/clusters/powerwall-blend.mpcdi is what scripts/make_blend_mpcdi.py writes;
#   - `cavelight-master --config configs/clusters/powerwall-blend-local.json --spawn-local
#     --output png --pattern` writes blended images whose overlap checks pass, against the
#     same run with the warps taken out of the config: outside the overlap each projector
#     shows the pattern as drawn; inside, each one's light is its alpha times the pattern's,
#     and where the two unblended images agree the two projectors' light adds up to it;
#   - --pattern-blend tints the overlap and nothing else;
#   - a warp mesh that mirrors the image mirrors it;
#   - a broken MPCDI file stops its node at start with one line naming the file and part.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/cluster_lib.sh"
root=$(cd "$here/../.." && pwd)
config="$root/configs/clusters/powerwall-blend-local.json"

python3 - "$root" "$tmp" <<'PY' || fail "the committed MPCDI differs from scripts/make_blend_mpcdi.py's"
import sys, zipfile, zlib
root, tmp = sys.argv[1], sys.argv[2]
sys.path.insert(0, root + "/scripts")
import make_blend_mpcdi
def members(path):
    with zipfile.ZipFile(path) as z:
        return {n: z.read(n) for n in z.namelist()}
def idat(png):  # the pixels, whatever the compressor's bytes
    i, data = 8, b""
    while i < len(png):
        n = int.from_bytes(png[i:i + 4], "big")
        if png[i + 4:i + 8] == b"IDAT":
            data += png[i + 8:i + 8 + n]
        i += 12 + n
    return zlib.decompress(data)
have, want = members(root + "/configs/clusters/powerwall-blend.mpcdi"), make_blend_mpcdi.members()
assert sorted(have) == sorted(want), (sorted(have), sorted(want))
for name in want:
    same = idat(have[name]) == idat(want[name]) if name.endswith(".png") else have[name] == want[name]
    assert same, name
print("powerwall-blend.mpcdi: the generator's %d members" % len(want))
PY

# run NAME CONFIG [MASTER OPTIONS...]: the must-show command, from a scratch folder, on any free port.
run() {
  local name=$1 cfg=$2; shift 2
  (cd "$tmp" && "$build/cavelight-master" --config "$cfg" --bind 'tcp://127.0.0.1:*' --spawn-local \
     --output png --out "$tmp/$name" "$@") > "$tmp/$name.log" 2>&1 || { cat "$tmp/$name.log"; fail "$name: master failed"; }
}
# edit NAME PYTHON: a copy of the shipped config in the test's folder, its warp files found
# where the shipped one finds them, then changed by PYTHON on c.
edit() {
  python3 - "$config" "$tmp/$1.json" "$2" <<'PY'
import json, os, sys
c = json.load(open(sys.argv[1]))
for n in c["nodes"]:
    w = n["screens"][0].get("warp", {})
    if "mpcdi" in w:
        w["mpcdi"] = os.path.join(os.path.dirname(sys.argv[1]), w["mpcdi"])
exec(sys.argv[3])
json.dump(c, open(sys.argv[2], "w"))
PY
}

run blend "$config" --pattern
edit plain 'for n in c["nodes"]: n["screens"][0].pop("warp")'
run plain "$tmp/plain.json" --pattern
run regions "$config" --pattern-blend

python3 - "$root" "$tmp" <<'PY' || fail "overlap checks"
import sys
root, tmp = sys.argv[1], sys.argv[2]
sys.path[:0] = [root + "/scripts", root + "/tests/integration"]
import make_blend_mpcdi as g
from png_rows import read_png

light = lambda v: (v / 255.0) ** g.GAMMA
W, H, O = g.WIDTH, g.HEIGHT, g.OVERLAP
first = {"l": W - O, "r": 0}  # each projector's first overlap column
# The alpha each projector column really has: the stored 8-bit value, gamma embedded.
alpha = {s: [(round(255 * g.alpha(r, x) ** (1 / g.GAMMA)) / 255.0) ** g.GAMMA for x in range(W)]
         for s, r in (("l", "left"), ("r", "right"))}
alpha_sum = max(abs(alpha["l"][W - O + k] + alpha["r"][k] - 1) for k in range(O))
step = 0.5 * g.GAMMA / 255  # half an 8-bit step, in light, at most
worst_each = worst_sum = 0.0
agree = total = 0
for eye in ("left", "right"):
    img = {(k, s): read_png("%s/%s/wall-%s-%s.png" % (tmp, k, s, eye))[2]
           for k in ("blend", "plain", "regions") for s in "lr"}
    for s in "lr":
        tinted = 0
        for y in range(H):
            for x in range(W):
                for c in range(3):
                    b, u, t = (img[k, s][y][3 * x + c] for k in ("blend", "plain", "regions"))
                    if not first[s] <= x < first[s] + O:
                        assert b == u and t == u, ("changed outside the overlap", eye, s, x, y, b, u, t)
                    else:
                        worst_each = max(worst_each, abs(light(b) - alpha[s][x] * light(u)))
                        tinted += t != u
        assert tinted > H * O, ("--pattern-blend left the overlap as it was", eye, s, tinted)
    for y in range(H):
        for k in range(O):  # the same CAVE column in both projectors
            col = {s: 3 * (first[s] + k) for s in "lr"}
            pl, pr = (img["plain", s][y][col[s]:col[s] + 3] for s in "lr")
            total += 1
            if pl != pr:
                continue  # the screens' corner labels differ there
            agree += 1
            for c in range(3):
                got = light(img["blend", "l"][y][col["l"] + c]) + light(img["blend", "r"][y][col["r"] + c])
                worst_sum = max(worst_sum, abs(got - light(pl[c])))
print("overlap: each projector's light = alpha x unblended within %.4f (bound %.4f); the two add up to the "
      "unblended light within %.4f (bound %.4f) on %d of %d overlap pixels (elsewhere the screens' labels differ)"
      % (worst_each, step, worst_sum, 2 * step + alpha_sum, agree, total))
assert worst_each <= step + 1e-9, worst_each
assert worst_sum <= 2 * step + alpha_sum + 1e-9, worst_sum
assert agree >= total * 0.6, (agree, total)
PY

# A warp mesh mirroring the left projector's image: u = 1 - x.
cat > "$tmp/mirror.warp" <<'MESH'
cavelight-warp-mesh 1
grid 2 2
0 0 1 0 1
1 0 0 0 1
0 1 1 1 1
1 1 0 1 1
MESH
edit mirror "c['nodes'][0]['screens'][0]['warp'] = {'mesh': '$tmp/mirror.warp'}"
run mirror "$tmp/mirror.json" --pattern
python3 - "$root" "$tmp" <<'PY' || fail "the mirror mesh"
import sys
sys.path.insert(0, sys.argv[1] + "/tests/integration")
from png_rows import read_png
w, h, m = read_png(sys.argv[2] + "/mirror/wall-l-left.png")
_, _, p = read_png(sys.argv[2] + "/plain/wall-l-left.png")
worst = max(abs(m[y][3 * x + c] - p[y][3 * (w - 1 - x) + c]) for y in range(h) for x in range(w) for c in range(3))
assert worst <= 1, worst
print("mirror mesh: the image mirrored, within %d code value" % worst)
PY

# A broken MPCDI: its node stops at start, in one line naming the file and the part.
head -c 300 "$root/configs/clusters/powerwall-blend.mpcdi" > "$tmp/broken.mpcdi"
edit broken "c['nodes'][1]['screens'][0]['warp']['mpcdi'] = '$tmp/broken.mpcdi'"
(cd "$tmp" && "$build/cavelight-master" --config "$tmp/broken.json" --bind 'tcp://127.0.0.1:*' --spawn-local \
   --output png --out "$tmp/broken" --pattern) > "$tmp/broken.log" 2>&1 || true
grep -q "cavelight-node: MPCDI $tmp/broken.mpcdi: archive: not a zip archive" "$tmp/broken.log" \
  || { cat "$tmp/broken.log"; fail "the broken MPCDI was not refused in one line"; }
grep -q "node right exited.* before joining" "$tmp/broken.log" || { cat "$tmp/broken.log"; fail "the master did not name the node"; }
echo "broken MPCDI: $(grep -m1 "cavelight-node: MPCDI" "$tmp/broken.log")"

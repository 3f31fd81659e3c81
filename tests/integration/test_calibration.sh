#!/usr/bin/env bash
# The calibration procedure of docs/calibration.md, end to end: the master prints the wand
# in tracker and CAVE space (--print-poses), and scripts/fit_tracker.py turns measured
# pairs back into the config's tracker_to_cave.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/cluster_lib.sh"
root=$(cd "$here/../.." && pwd)

# A config whose tracker sits 1.5 m behind the CAVE's origin, turned and tilted.
make_config "$tmp/c.json" 20000 a
python3 - "$tmp/c.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c["observer"]["tracker_to_cave"] = {"translation": [0.2, -0.1, 1.5], "rotation_deg": [10, -35, 5], "scale": 1.0}
json.dump(c, open(sys.argv[1], "w"))
PY
# Four wand positions (CAVE space, as a playback recording holds them), 16 polls each.
python3 - "$tmp/rec.txt" <<'PY'
import sys
points = [(0.5, 1.0, -1.0), (-1.2, 0.3, 0.4), (0.0, 2.5, -1.4), (1.1, 0.0, 1.2)]
with open(sys.argv[1], "w") as f:
    f.write("cavelight-input 1\n")
    for i in range(64):
        t = i / 8.0
        x, y, z = points[i // 16]
        f.write("wand %.9g %g %g %g 1 0 0 0 1 0 0 0 1\npoll %.9g %.9g\n" % (t, x, y, z, t, 0 if i == 0 else 0.125))
PY
"$build/cavelight-master" --config "$tmp/c.json" --bind 'tcp://127.0.0.1:*' --spawn-local --render none \
    --input "$tmp/rec.txt" --print-poses --fps 8 --quiet > "$tmp/poses.txt" 2> "$tmp/master.log" \
    || { cat "$tmp/master.log"; fail "master failed"; }
[ "$(grep -c ' wand cave ' "$tmp/poses.txt")" -ge 8 ] || { cat "$tmp/poses.txt"; fail "too few pose lines"; }
# The pairs a person would write down: tracker and CAVE columns of each position.
python3 - "$tmp/poses.txt" "$tmp/pairs.txt" <<'PY'
import sys
pairs = {}
for line in open(sys.argv[1]):
    w = line.split()
    i = w.index("wand")
    cave = tuple(w[i + 2:i + 5]); tracker = tuple(w[i + 6:i + 9])
    assert w[i + 1] == "cave" and w[i + 5] == "tracker", line
    pairs[cave] = tracker
assert len(pairs) == 4, pairs
with open(sys.argv[2], "w") as f:
    for cave, tracker in pairs.items():
        f.write("%s  %s\n" % (" ".join(tracker), " ".join(cave)))
PY
python3 "$root/scripts/fit_tracker.py" "$tmp/pairs.txt" > "$tmp/fit.txt" || fail "fit_tracker failed"
python3 - "$tmp/fit.txt" <<'PY' || { cat "$tmp/fit.txt"; fail "fit_tracker did not recover tracker_to_cave"; }
import json, sys
line = open(sys.argv[1]).readline()
fit = json.loads(line.split(":", 1)[1])
want = {"translation": [0.2, -0.1, 1.5], "rotation_deg": [10, -35, 5], "scale": 1.0}
assert all(abs(a - b) < 1e-3 for a, b in zip(fit["translation"], want["translation"])), fit
assert all(abs(a - b) < 0.05 for a, b in zip(fit["rotation_deg"], want["rotation_deg"])), fit
assert abs(fit["scale"] - 1) < 1e-3, fit
PY
head -1 "$tmp/fit.txt"
# Refusals: --print-poses needs input; a bad pairs file is one line.
"$build/cavelight-master" --config "$tmp/c.json" --print-poses 2> "$tmp/err" && fail "--print-poses without --input ran"
grep -q "add --input" "$tmp/err" || fail "no hint: $(cat "$tmp/err")"
echo "1 2 3" > "$tmp/bad.txt"
python3 "$root/scripts/fit_tracker.py" "$tmp/bad.txt" 2> "$tmp/err" && fail "a bad pairs file was taken"
grep -q "bad.txt:1: give six numbers" "$tmp/err" || fail "fit_tracker error: $(cat "$tmp/err")"
echo "calibration: print-poses and fit_tracker recover tracker_to_cave"

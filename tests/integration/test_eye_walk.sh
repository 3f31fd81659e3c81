#!/usr/bin/env bash
# Head poses never end a session: a recorded head walks the eyes through every screen
# plane of configs/clusters/cave5-local.json (front, both sides, floor, ceiling; on the
# plane, 2 cm in front, behind it), then sends poses no tracker should: 500 m away, a
# mirrored and a sheared rotation. The ten nodes render every frame, none is lost, each
# says once (rate-limited) that it moved an eye in front of its screen, and the master
# says it replaced the absurd poses.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/cluster_lib.sh"
root=$(cd "$here/../.." && pwd)

python3 - "$tmp/walk.txt" <<'PY'
import sys
# head_to_eye (0, -0.06, -0.08), eyes 0.032 m either side: the head positions that put
# the eyes on each plane, and 0.3 m either side of it in 2.5 cm steps.
walks = [(2, -1.5 + 0.08, +1), (0, -1.5, +1), (0, 1.5, -1), (1, 0.0 + 0.06, +1), (1, 3.0 + 0.06, -1)]
I = [1, 0, 0, 0, 1, 0, 0, 0, 1]
poses = []
for axis, on_plane, inward in walks:
    for k in range(-12, 13):
        p = [0.0, 1.7, 0.0]
        p[axis] = on_plane - inward * k * 0.025
        poses.append((p, I))
poses.append(([500.0, 1.7, 0.0], I))                       # absurd: replaced
poses.append(([0.0, 1.7, 0.0], [-1, 0, 0, 0, 1, 0, 0, 0, 1]))   # mirrored: replaced
poses.append(([0.0, 1.7, 0.0], [1, 0, 0, 0.05, 1, 0, 0, 0, 1])) # sheared: repaired
with open(sys.argv[1], "w") as f:
    f.write("cavelight-input 1\n")
    for i, (p, r) in enumerate(poses):
        t = i / 30.0
        f.write("head %.9g %s %s\n" % (t, " ".join("%.9g" % v for v in p), " ".join("%.9g" % v for v in r)))
        f.write("poll %.9g %.9g\n" % (t, 0 if i == 0 else 1 / 30.0))

PY
frames=$(grep -c '^poll' "$tmp/walk.txt")
start=$(date +%s)
"$build/cavelight-master" --config "$root/configs/clusters/cave5-local.json" --bind 'tcp://127.0.0.1:*' \
    --spawn-local --input "$tmp/walk.txt" --output headless --report "$tmp/r.json" --out "$tmp/out" \
    --lattice 8 --rsm 32 --node-args "--threads 1" --quiet 2> "$tmp/master.log" \
    || { tail -30 "$tmp/master.log"; fail "the master failed"; }
[ "$(json 'r["frames"]' "$tmp/r.json")" = "$frames" ] || fail "not $frames frames: $(json 'r["frames"]' "$tmp/r.json")"
[ "$(json 'r["drops"]' "$tmp/r.json")" = 0 ] || { cat "$tmp/master.log"; fail "a node was dropped"; }
[ "$(json 'r["nodes_live_min"]' "$tmp/r.json")" = 10 ] || fail "fewer than 10 nodes live at some frame"
[ "$(json 'min(n["frames_ready"] for n in r["per_node"])' "$tmp/r.json")" = "$frames" ] || fail "a node missed frames"
[ "$(json 'r["desyncs"]' "$tmp/r.json")" = 0 ] || fail "desync"
for s in front-l front-r left-b left-f right-f right-b floor-f floor-b ceiling-f ceiling-b; do
    grep -q "the plane of screen $s: rendered from 0.02 m in front" "$tmp/master.log" \
        || { cat "$tmp/master.log"; fail "no node reported an eye moved in front of $s"; }
done
lines=$(grep -c "rendered from 0.02 m in front" "$tmp/master.log")
# ratelog: per node a burst of 5 lines, then at most one per 10 s of the run (however
# long a loaded machine makes it), against one line per frame without it
secs=$(( $(date +%s) - start + 1 ))
most=$(( 10 * (5 + secs / 10 + 1) ))
[ "$lines" -le "$most" ] && [ "$most" -lt $(( 10 * frames )) ] \
    || fail "$lines eye lines in $secs s (at most $most): not rate-limited"
grep -q "head pose replaced by the last good one: the position (500, 1.7, 0) m lies outside" "$tmp/master.log" \
    || fail "the absurd pose was not replaced"
grep -q "head pose replaced by the last good one: the rotation is no rotation" "$tmp/master.log" \
    || fail "the mirrored rotation was not replaced"
grep -q "head pose rotation made orthonormal" "$tmp/master.log" || fail "the sheared rotation was not repaired"
echo "eye walk: $frames frames through 5 planes and 3 bad poses, 10 nodes, none lost, $lines eye lines"

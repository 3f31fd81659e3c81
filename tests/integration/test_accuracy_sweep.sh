#!/usr/bin/env bash
# cavelight-bench accuracy (the measuring half of scripts/chart.sh) at a tiny size: every
# experiment writes its CSV and JSON line, both transports are swept alike (--transports),
# the Pareto marks (on the indirect relative RMSE
# the CSV prints) are right, the goal's rows are run and summarised, the metrics are
# masked to geometry (the open courtyard's sky is left out), the reference cache is
# reused, the caches method's rows (one with every RSM texel, one selected, against it), and
# scripts/accuracy_report.py turns the output into markdown with the goal table and the
# three methods' table.
set -euo pipefail
build=$1
src=$(cd "$(dirname "$0")/../.." && pwd)
bench="$build/cavelight-bench"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
command -v python3 >/dev/null || { echo "python3 missing: skipped"; exit 77; }
small=(--width 40 --height 30 --out "$out" --threads 1)

"$bench" accuracy sweep --scene default "${small[@]}" --ref-samples 4 --lattices 8,12 \
    --steps 1,4,8 --lambdas 0,0.8 --backends cpu --transports beams,paper --timing-frames 2 \
    > "$out/sweep.json" \
    2> "$out/sweep.log" || { cat "$out/sweep.log" >&2; fail "sweep failed"; }
ls "$out"/ref_default_a_40x30_4_direct.pfm "$out"/ref_default_a_40x30_4_noise.txt \
    "$out"/ref_default_a_40x30_4_coverage.pfm >/dev/null || fail "reference not cached"
python3 - "$out" <<'PY' || fail "sweep CSV or summary wrong"
import csv, json, math, sys
out = sys.argv[1]
rows = list(csv.DictReader(open(f"{out}/sweep_default.csv")))
# 2 transports x 2 lattices x (3 steps x 2 lambdas + 3 classic) configurations, then the
# goal's (beams): 4 steps at the default lambda_incr 0.8 on 16, 32 and 64 cells.
assert len(rows) == 39, len(rows)
for t in ("beams", "paper"):
    mine = [(r["lattice"], r["mode"], r["steps"], r["lambda"]) for r in rows
            if r["transport"] == t and r["lattice"] in ("8", "12")]
    assert len(mine) == 18 and len(set(mine)) == 18, (t, mine)
for r in rows:
    assert r["backend"] == "cpu" and r["mode"] in ("incremental", "classic")
    for k in ("propagate_ms", "frame_ms", "mae_display", "mae_indirect", "ssim_indirect",
              "rmse_rel_indirect"):
        assert math.isfinite(float(r[k])) and float(r[k]) >= 0, (k, r[k])
    assert 0 < float(r["mae_display"]) < 1 and float(r["ssim_indirect"]) <= 1
    assert (r["mode"] == "classic") == (r["mae_self32"] == "nan")
    assert r["frames"] == ("33" if r["lambda"] == "0.8" else "3"), r  # 31 to steady state, 2 timed
goal = [r for r in rows if r["lattice"] in ("16", "32", "64")]
assert all(r["transport"] == "beams" for r in goal)
assert [(r["lattice"], r["steps"], r["lambda"]) for r in goal] == \
    [("16", "4", "0.8"), ("32", "4", "0.8"), ("64", "4", "0.8")], goal
def dominated(a, b):  # b at least as fast and as accurate, and better in one
    ta, ea, tb, eb = (float(a["propagate_ms"]), float(a["rmse_rel_indirect"]),
                      float(b["propagate_ms"]), float(b["rmse_rel_indirect"]))
    return tb <= ta and eb <= ea and (tb < ta or eb < ea)
for a in rows:
    on_front = not any(dominated(a, b) for b in rows if b is not a)
    assert on_front == (a["pareto"] == "1"), a
j = json.loads(open(f"{out}/sweep.json").read())
assert j["configs"] == 39 and j["reference_noise_indirect1"] > 0 and j["reference_seconds"] > 0
assert j["reference_cached"] is False and j["pixels_compared"] == 40 * 30  # a closed room
g = j["goal"]
assert (g["lattice"], g["steps"], g["lambda"], g["lattices"]) == (32, 4, 0.8, [16, 32, 64]), g
assert g["rmse_rel"] == float(goal[1]["rmse_rel_indirect"]) and g["no_signal"] is False
assert abs(g["ssim"] - float(goal[1]["ssim_indirect"])) <= 1e-5 and g["propagate_ms"] > 0
by = [g["rmse_rel_16"], g["rmse_rel_32"], g["rmse_rel_64"]]
assert g["finer_never_worse"] == (by[1] <= by[0] and by[2] <= by[1]), g
# Debiased: raw^2 - debiased^2 is the reference's noise relRMSE squared (or debiased is 0).
noise = j["reference_noise_rel"]
assert 0 < noise < 2 and j["reference_samples"] == 8, j
for r in rows:
    raw, deb = float(r["rmse_rel_indirect"]), float(r["rmse_rel_debiased_indirect"])
    assert 0 <= deb <= raw, r
    assert deb == 0 or abs(raw * raw - deb * deb - noise * noise) < 1e-4 * max(1, raw * raw), (r, noise)
    assert 0 < float(r["flip_indirect"]) < 1, r
assert abs(g["rmse_rel_debiased"] - float(goal[1]["rmse_rel_debiased_indirect"])) < 1e-5, g
assert abs(g["flip"] - float(goal[1]["flip_indirect"])) < 1e-5, g
PY

# The reference alone, in rounds to a noise target: more paths than the first round's, the
# noise at or below the target, the count cached with it; one round by default.
"$bench" accuracy reference --scene default "${small[@]}" --ref-samples 2 --ref-noise 0.3 \
    > "$out/reference.json" 2> "$out/reference.log" || { cat "$out/reference.log" >&2; fail "reference failed"; }
"$bench" accuracy reference --scene default "${small[@]}" --ref-samples 2 --ref-noise 0.3 \
    > "$out/reference_again.json" 2>/dev/null || fail "cached reference failed"
"$bench" accuracy reference --scene default "${small[@]}" --ref-samples 2 \
    > "$out/reference_one.json" 2>/dev/null || fail "one-round reference failed"
python3 - "$out" <<'PY' || fail "reference rounds wrong"
import json, sys
out = sys.argv[1]
r, again, one = (json.loads(open(f"{out}/{n}.json").read())
                 for n in ("reference", "reference_again", "reference_one"))
assert one["reference_samples"] == 4 and one["reference_noise_rel"] > 0.3, one
assert r["reference_samples"] > 4 and r["reference_noise_rel"] <= 0.3, r
assert again["reference_cached"] is True and again["reference_samples"] == r["reference_samples"], again
assert abs(again["reference_noise_rel"] - r["reference_noise_rel"]) < 1e-6, again
PY
grep -q "reference noise relRMSE .* at 2 paths per half" "$out/reference.log" || fail "no round printed"

# Masked to geometry: from the open courtyard's camera some pixels see the sky; the
# metrics count only the others.
"$bench" accuracy sweep --scene courtyard "${small[@]}" --ref-samples 2 --lattices 8 \
    --steps 1 --lambdas 0 --backends cpu --classic 0 --goal 0 --timing-frames 1 \
    > "$out/court.json" 2>/dev/null || fail "courtyard sweep failed"
python3 - "$out" <<'PY' || fail "courtyard metrics are not masked to geometry"
import json, struct, sys
out = sys.argv[1]
def pfm(path):
    f = open(path, "rb"); f.readline()
    w, h = map(int, f.readline().split()); f.readline()
    return struct.unpack("<%df" % (w * h * 3), f.read(w * h * 12))
cov = pfm(f"{out}/ref_courtyard_a_40x30_2_coverage.pfm")[::3]
assert set(cov) <= {0.0, 1.0} and 0 < sum(cov) < len(cov), sum(cov)
j = json.loads(open(f"{out}/court.json").read())
assert j["pixels_compared"] == sum(cov), (j["pixels_compared"], sum(cov))
PY

# A second run reads the cached reference instead of tracing it again (the first run's
# CSV is kept for the report below).
cp "$out/sweep_default.csv" "$out/first.csv"
"$bench" accuracy sweep --scene default "${small[@]}" --ref-samples 4 --lattices 8 \
    --steps 1 --lambdas 0 --backends cpu --classic 0 --goal 0 --timing-frames 1 \
    > "$out/again.json" 2>/dev/null || fail "second sweep failed"
python3 -c "import json,sys; assert json.load(open(sys.argv[1]))['reference_cached'] is True" \
    "$out/again.json" || fail "the cached reference was not reused"
mv "$out/first.csv" "$out/sweep_default.csv"

"$bench" accuracy move --scene default "${small[@]}" --ref-samples 4 --lattice 8 --steps 2 \
    --lambdas 0,0.8 --frames 6 > "$out/move_default.json" 2>/dev/null || fail "move failed"
"$bench" accuracy path --scene default "${small[@]}" --lattice 8 --steps 2 --lambdas 0.8 \
    --frames 6 > "$out/path_default.json" 2>/dev/null || fail "path failed"
"$bench" accuracy savings --scene default "${small[@]}" --lattice 8 --frames 40 \
    > "$out/savings_default.json" 2>/dev/null || fail "savings failed"
CAVELIGHT_CACHE_DIR="$out/light-caches" "$bench" accuracy caches --scene default "${small[@]}" \
    --ref-samples 4 --rsm 64 --vals 256 --occlusion approx --frames 1 --temporal-frames 3 \
    > "$out/caches_default.json" \
    2> "$out/caches.log" || { cat "$out/caches.log" >&2; fail "caches failed"; }
cp "$out/sweep.json" "$out/sweep_default.json"
python3 - "$out" <<'PY' || fail "caches output wrong"
import csv, json, math, sys
out = sys.argv[1]
rows = list(csv.DictReader(open(f"{out}/caches_default.csv")))
assert [(r["selection"], r["vals"]) for r in rows] == [("all", "all"), ("importance", "256")], rows
for r in rows:
    for k in ("gi_ms", "rmse_rel_indirect", "ssim_indirect", "reference_noise_rel"):
        assert math.isfinite(float(r[k])) and float(r[k]) > 0, (k, r[k])
    assert int(r["caches"]) > 0 and r["occlusion"] == "approx" and r["rsm"] == "64"
assert float(rows[1]["speedup"]) > 0 and float(rows[1]["rmse_rel_vs_all"]) > 0
assert rows[0]["speedup"] == "nan" and float(rows[1]["importance_ms"]) > 0
lines = [json.loads(l) for l in open(f"{out}/caches_default.json")]
assert len(lines) == 3 and lines[1]["speedup"] == float(rows[1]["speedup"])
t = lines[2]
assert t["experiment"] == "caches_temporal" and t["static_identical"] is True, t
assert t["light_max_change_indirect"] > 0 and t["head_max_change_indirect"] > 0
assert t["head_max_change_direct"] == 0  # the head moves, the camera does not
assert len(list(csv.DictReader(open(f"{out}/caches_temporal_default.csv")))) == 2 * 2
PY
python3 - "$out" <<'PY' || fail "move, path or savings output wrong"
import csv, json, sys
out = sys.argv[1]
move = list(csv.DictReader(open(f"{out}/move_default.csv")))
assert len(move) == 3 * 6  # lambda 0, lambda 0.8, classic; 6 frames each
lat = [float(r["lattice_change"]) for r in move if r["lambda"] == "0.8"]
assert lat[0] > lat[-1], lat  # converging towards the new steady state
path = list(csv.DictReader(open(f"{out}/path_default.csv")))
assert len(path) == 2 * 6 and all(float(r["change_direct"]) > 0 for r in path)
s = json.loads(open(f"{out}/savings_default.json").read())
assert s["frames_skipped"] > 0 and s["frames_skipped_when_off"] == 0
# The time skipping saves is the benchmark's figure, not asserted: under load it flips.
assert s["frame_pass_ms_total_skip"] >= 0 and s["frame_pass_ms_total_no_skip"] > 0
assert s["cells"] <= s["cube_cells"]
PY
python3 "$src/scripts/accuracy_report.py" "$out" --quick > "$out/ACCURACY.md" \
    || fail "report generator failed"
grep -q "^## default: speed against accuracy" "$out/ACCURACY.md" || fail "report lacks the sweep"
grep -q "^| default | [0-9.]* (raw [0-9.]*, FLIP [0-9.]*) | .* | [0-9.]* / [0-9.]* / [0-9.]* | .* |$" "$out/ACCURACY.md" \
    || fail "report lacks the goal table"
grep -q "Modelling no more than the scene needs" "$out/ACCURACY.md" || fail "report lacks savings"
grep -q "^| every texel | approx | 64 | " "$out/ACCURACY.md" || fail "report lacks the caches rows"
grep -q "^## Three methods: ILPV, vpl and caches" "$out/ACCURACY.md" || fail "report lacks the method table"
grep -q "^| default | yes | " "$out/ACCURACY.md" || fail "report lacks the caches' temporal table"
grep -q "^| default | 8 | .* | [0-9.]* |$" "$out/ACCURACY.md" || fail "report lacks the reference noise table"
echo "accuracy sweep: ok"

#!/usr/bin/env bash
# scripts/gpu_check.sh --dry-run on llvmpipe: every case of the GPU check at a small size
# on the built-in room (the arcades and the street add minutes of the caches' placement on
# 2 cores), one JSON file with a run per case, each with GPU ms per stage, and the table.
set -euo pipefail
build=$1
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
root=$(cd "$(dirname "$0")/../.." && pwd)
"$root/scripts/gpu_check.sh" --dry-run --scenes default --build "$build" --out "$out" || fail "gpu_check.sh --dry-run failed"
python3 - "$out" <<'PY' || fail "gpu_check.json or gpu.md incomplete"
import json, sys
out = sys.argv[1]
d = json.load(open(f"{out}/gpu_check.json"))
assert d["dry_run"] is True
runs = d["runs"]
assert {r["scene"] for r in runs} == {"default"}, "scenes"
assert len(runs) == 13, len(runs)
for r in runs:
    g = r["gpu_ms"]
    for stage in ("rsm", "gi", "gbuffer", "shade", "final"):
        assert stage in g and g[stage] >= 0, (r["scene"], r["case"], stage)
    if r["case"].startswith("ilpv"):
        assert "inject" in g and "propagate" in g, r["case"]
table = open(f"{out}/gpu.md").read().splitlines()
assert len(table) == 2 + len(runs), len(table)
print(f"{len(runs)} runs, every one with gpu_ms per stage")
PY

#!/usr/bin/env bash
# The GPU check (issue 30, item 5): one prepared run for a machine with a GPU and no
# package access (scripts/bundle.sh carries the programs). Every GI method at its default
# settings and at its smallest ones, ILPV on both backends and transports, and both AO
# stages, on the built-in room, the arcades and the street, 1920x1200 per eye: one
# `cavelight-bench frame` each (GPU ms per stage from timer queries, host ms beside).
# Writes OUT/gpu_check.json (every bench line, one array) and OUT/gpu.md (the table of
# docs/gpu.md). The bench renders one eye per frame: the table's stereo frame is the frame
# pass plus twice the eye passes' GPU ms, computed, not measured.
#
#   scripts/gpu_check.sh [--build DIR] [--out DIR] [--dry-run] [--scenes A,B,...]
#
# --scenes: only these of the three (test_gpu_check: the room, to stay short).
# --dry-run: the same steps at 32x20 with 32x32 RSMs, 3 frames, on whatever GL there is
# (llvmpipe in the tests: test_gpu_check), so the script works the first time it meets a
# GPU.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$root/build out=$root/out/gpu_check dry=0
while [ $# -gt 0 ]; do
    case $1 in
        --build) build=$2; shift 2 ;;
        --out) out=$2; shift 2 ;;
        --dry-run) dry=1; shift ;;
        --scenes) IFS=, read -r -a only <<< "$2"; shift 2 ;;
        *) echo "gpu_check: unknown argument $1 (--build DIR, --out DIR, --dry-run, --scenes LIST)" >&2; exit 2 ;;
    esac
done
bench=$build/cavelight-bench
[ -x "$bench" ] || { echo "gpu_check: $bench missing: build first" >&2; exit 1; }
size=(--width 1920 --height 1200) frames=12
[ $dry = 1 ] && size=(--width 32 --height 20 --rsm 32) frames=3
mkdir -p "$out"
export CAVELIGHT_CACHE_DIR=${CAVELIGHT_CACHE_DIR:-$out/cache}

# name|bench options: defaults, then the smallest settings of each method.
cases=(
    "ilpv-cpu-beams|--gi ilpv --lpv cpu --lpv-transport beams"
    "ilpv-cpu-paper|--gi ilpv --lpv cpu --lpv-transport paper"
    "ilpv-gl-beams|--gi ilpv --lpv gl --lpv-transport beams"
    "ilpv-gl-paper|--gi ilpv --lpv gl --lpv-transport paper"
    "ilpv-gl-16-1|--gi ilpv --lpv gl --lattice 16 --steps 1"
    "vpl|--gi vpl"
    "vpl-64|--gi vpl --vpl-count 64"
    "caches|--gi caches"
    "caches-256|--gi caches --caches-vals 256"
    "ldm|--gi ldm"
    "ldm-16|--gi ldm --ldm-directions 16"
    "ao-ldm|--gi none --ao ldm"
    "ao-ssao|--gi none --ao ssao"
)
scenes=(default arcades street)
[ -n "${only+x}" ] && scenes=("${only[@]}")
started=$(date +%s)
lines=$out/lines.jsonl
: > "$lines"
for scene in "${scenes[@]}"; do
    for c in "${cases[@]}"; do
        name=${c%%|*}
        # shellcheck disable=SC2086
        if ! line=$("$bench" frame --scene "$scene" "${size[@]}" --frames $frames ${c#*|} 2> "$out/$scene-$name.log"); then
            echo "gpu_check: $scene $name failed (see $out/$scene-$name.log)" >&2
            exit 1
        fi
        printf '{"case":"%s",%s\n' "$name" "${line#\{}" >> "$lines"
        echo "gpu_check: $scene $name done ($(( $(date +%s) - started )) s)" >&2
    done
done

python3 - "$lines" "$out" "$dry" <<'EOF'
import json, sys
lines, out, dry = sys.argv[1], sys.argv[2], sys.argv[3] == "1"
rows = [json.loads(l) for l in open(lines)]
json.dump({"dry_run": dry, "runs": rows}, open(f"{out}/gpu_check.json", "w"), indent=1)
frame_stages, eye_stages = ("rsm", "gi"), ("gbuffer", "ao", "shade", "final")
head = ("| scene | case | renderer | size | rsm | gi | method's stages (GPU ms) | gbuffer | ao "
        "| shade | final | stereo frame (GPU ms, computed) | frame pass host ms | eye pass host ms |")
md = [head, "|" + " --- |" * (head.count("|") - 1)]
for r in rows:
    g = r.get("gpu_ms", {})
    own = ", ".join(f"{k} {v:.2f}" for k, v in g.items() if k not in frame_stages + eye_stages)
    stereo = sum(g.get(k, 0) for k in frame_stages) + 2 * sum(g.get(k, 0) for k in eye_stages)
    cells = [r["scene"], r["case"], r["renderer"], f'{r["width"]}x{r["height"]}']
    cells += [f"{g.get(k, 0):.2f}" for k in frame_stages] + [own or "-"]
    cells += [f"{g.get(k, 0):.2f}" for k in eye_stages]
    cells += [f"{stereo:.2f}", f'{r["frame_host_ms"]:.2f}', f'{r["eye_host_ms"]:.2f}']
    md.append("| " + " | ".join(cells) + " |")
open(f"{out}/gpu.md", "w").write("\n".join(md) + "\n")
print(f"gpu_check: {len(rows)} runs: {out}/gpu_check.json, {out}/gpu.md", file=sys.stderr)
EOF
echo "gpu_check: $(( $(date +%s) - started )) s in all" >&2

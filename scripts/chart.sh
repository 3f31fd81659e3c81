#!/usr/bin/env bash
# Speed against accuracy of the GI methods (ILPV, vpl, caches, ldm) on the built-in chart
# scenes (default room, corridor, doorway, courtyard, arcades, street block) and any glTF
# file given with --scene: sweeps lattice size, steps per frame, lambda_incr, the CPU and GL
# backends, the classic accumulating LPV and both LPV transports (beams, ours; paper, the
# thesis's), the vpl method's VPL counts, the caches method's VALs and occlusion and the
# ldm method's maps, against a path-traced (Embree) reference, every scene with the same
# settings; and the layered depth maps' ambient occlusion against the screen-space baseline
# at several distance limits. Accuracy is the
# indirect image's relative RMSE (raw, and debiased by the reference's own noise: docs/
# accuracy-metrics.md) and SSIM against the reference's one-bounce image over
# the pixels that meet geometry. Also measures the error after an abrupt light move and
# the frame-to-frame change along a light path; writes CSVs and PNG charts to OUT
# (default out/chart) and docs/ACCURACY.md with docs/accuracy/.
# The path-traced reference is cached in OUT as ref_*.pfm; --reuse-reference keeps it
# between runs (only when the scene, camera and reference code are unchanged).
# Its two halves get --ref-samples N paths per pixel each (QUICK_REF_SAMPLES /
# FULL_REF_SAMPLES below), then more rounds until the reference's own noise (relRMSE of
# the averaged image, from the halves' difference) is at most --ref-noise T (0.03; 0: one
# round); each scene's reference is rendered first and its noise printed.
# --charts-only draws the charts and writes the docs again from what OUT holds.
# Usage: scripts/chart.sh [--quick] [--out DIR] [--no-docs] [--reuse-reference]
#                         [--ref-samples N] [--ref-noise T] [--charts-only]
#                         [--scene FILE.gltf]...
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
quick=0 docs=1 reuse=0 charts_only=0 out=$root/out/chart ref_samples= ref_noise=0.03
# The first round's paths per pixel per half (the issue-32 chart's were 32 and 256).
QUICK_REF_SAMPLES=256 FULL_REF_SAMPLES=256
scenes=(default corridor doorway courtyard arcades street)
usage="usage: scripts/chart.sh [--quick] [--out DIR] [--no-docs] [--reuse-reference] [--ref-samples N] [--ref-noise T] [--charts-only] [--scene FILE]..."
while [ $# -gt 0 ]; do
  case $1 in
    -h|--help) echo "$usage"; exit 0 ;;
    --quick) quick=1 ;;
    --no-docs) docs=0 ;;
    --reuse-reference) reuse=1 ;;
    --charts-only) charts_only=1 ;; # the charts and docs again from OUT's measurements
    --out) [ $# -ge 2 ] || { echo "$usage" >&2; exit 2; }; out=$2; shift ;;
    --ref-samples) [ $# -ge 2 ] && [[ $2 =~ ^[1-9][0-9]*$ ]] ||
                     { echo "chart: --ref-samples needs a positive number of paths per half" >&2; exit 2; }
                   ref_samples=$2; shift ;;
    --ref-noise) [ $# -ge 2 ] || { echo "$usage" >&2; exit 2; }; ref_noise=$2; shift ;;
    --scene) [ $# -ge 2 ] && [ -f "$2" ] || { echo "chart: --scene needs a glTF file" >&2; exit 2; }
             scenes+=("$(cd "$(dirname "$2")" && pwd)/$(basename "$2")"); shift ;;
    *) echo "$usage" >&2; exit 2 ;;
  esac
  shift
done
# Dependencies and the build once the arguments are known good (--help needs neither).
. "$root/scripts/deps.sh"
cavelight_install_deps
cavelight_build "$root" >/dev/null
mkdir -p "$out"
if [ $charts_only = 1 ]; then
  [ -f "$out/scenes.txt" ] || { echo "chart: --charts-only: no measurements in $out" >&2; exit 2; }
else
  rm -rf "$out"/*.csv "$out"/*.json "$out"/*.png "$out"/budget_* "$out"/scenes.txt
  [ $reuse = 1 ] || rm -f "$out"/ref_*
fi
# The name each scene's files carry (the bench's: a file's name without its extension).
key() { local b; b=$(basename "$1"); echo "${b%%.*}"; }

if [ $quick = 1 ]; then
  size=(--width 160 --height 120)
  ref=(--ref-samples "${ref_samples:-$QUICK_REF_SAMPLES}" --ref-noise "$ref_noise")
  sweep=(--lattices 16,32,64,fit --steps 1,2,4,8,16 --gl-max-lattice 16 --timing-frames 3)
  motion=(--frames 40)
  vpl=(--counts 64,256 --seeds 1 --visibility exact,ism,ism-splat --interleave 0,4)
  caches=(--vals 512,2048 --occlusion approx,exact --lightskin 0 --frames 2 --temporal-frames 10)
  ldm=(--configs 16:64,32:128 --ao-configs 32:64,64:128)
else
  size=(--width 320 --height 240)
  ref=(--ref-samples "${ref_samples:-$FULL_REF_SAMPLES}" --ref-noise "$ref_noise")
  sweep=(--lattices 16,32,64,fit --gl-max-lattice 32 --timing-frames 5)
  motion=(--frames 60)
  vpl=(--counts 64,256,1024 --seeds 2 --visibility exact,ism,ism-splat --ism-sizes 16,32
       --ism-points 256,1024 --interleave 0,4 --selection flux,view,regular)
  caches=(--vals 512,2048,8192 --occlusion approx,exact,off --lightskin 1 --frames 3 --temporal-frames 30)
  ldm=(--configs 16:64,32:128,64:128 --ao-configs 32:64,64:128,128:128)
fi
bench=$root/build/cavelight-bench
start=$SECONDS
measure() {
  for scene in "${scenes[@]}"; do
    k=$(key "$scene")
    echo "$k" >> "$out/scenes.txt"
    "$bench" accuracy reference --scene "$scene" --out "$out" "${size[@]}" "${ref[@]}" \
      > "$out/reference_$k.json"
    python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); print("chart: %s: reference noise relRMSE %.4f (%d paths per pixel, %.1f s%s)" % (sys.argv[2], j["reference_noise_rel"], j["reference_samples"], j["reference_seconds"], ", cached" if j["reference_cached"] else ""))' \
      "$out/reference_$k.json" "$k" >&2
    echo "chart: $k: sweep ($((SECONDS - start)) s)" >&2
    "$bench" accuracy sweep --scene "$scene" --out "$out" "${size[@]}" "${ref[@]}" "${sweep[@]}" \
      > "$out/sweep_$k.json"
    echo "chart: $k: light move and light path" >&2
    "$bench" accuracy move --scene "$scene" --out "$out" "${size[@]}" "${ref[@]}" "${motion[@]}" \
      > "$out/move_$k.json"
    "$bench" accuracy path --scene "$scene" --out "$out" "${size[@]}" "${motion[@]}" \
      > "$out/path_$k.json"
    "$bench" accuracy savings --scene "$scene" --out "$out" "${size[@]}" > "$out/savings_$k.json"
    echo "chart: $k: vpl" >&2
    "$bench" accuracy vpl --scene "$scene" --out "$out" "${size[@]}" "${ref[@]}" "${vpl[@]}" \
      > "$out/vpl_$k.json"
    echo "chart: $k: caches" >&2
    "$bench" accuracy caches --scene "$scene" --out "$out" "${size[@]}" "${ref[@]}" "${caches[@]}" \
      > "$out/caches_$k.json"
    echo "chart: $k: ldm and AO" >&2
    "$bench" accuracy ldm --scene "$scene" --out "$out" "${size[@]}" "${ref[@]}" "${ldm[@]}" \
      > "$out/ldm_$k.json"
  done
  echo "chart: frame-time budgets" >&2
  for budget in 5 10 20 40; do
    "$root/build/cavelight-node" --standalone --budget-ms $budget --frames 12 \
      --converge-threshold -1 "${size[@]}" --out "$out/budget_$budget" > /dev/null
  done
  # The thesis's Table 4.2: ms of 8 steps at 32^3 and 64^3, CPU (2 threads) and GL compute.
  echo "chart: steps of both transports" >&2
  for t in paper beams; do
    for b in cpu gl; do
      for res in 32 64; do
        "$bench" lpv --res $res --steps 8 --threads 2 --naive-repeats 1 --transport $t --backend $b ||
          echo "chart: lpv $t $b ${res}^3: GL and CPU differ beyond 1e-3 (its max_rel_diff_vs_cpu; docs/lpv.md)" >&2
      done
    done
  done > "$out/steps.json"
  echo "chart: measured in $((SECONDS - start)) s" >&2
}
[ $charts_only = 1 ] || measure

# Charts. Columns of sweep_*.csv: see the header line (11 propagate_ms, 14 frame_ms,
# 16 rmse_rel_indirect, 24 mae_self32, 25 pareto, 26 transport); of vpl_*.csv (2 vpl_count, 7 gi_ms,
# 8 frame_ms, 9 rmse_rel_indirect, 16 visibility, 17 ism_size, 18 ism_points, 19
# interleave, 28 selection); of caches_*.csv (2 vals, 3 selection, 4 occlusion, 13 gi_ms,
# 14 frame_ms, 15 rmse_rel_indirect); of ldm_*.csv (2 directions, 3 resolution, 9 gi_ms,
# 10 frame_ms, 12 rmse_rel_indirect); of ao_*.csv (2 method, 3 distance, 4 directions,
# 5 resolution, 6 ao_ms, 9 rmse_rel). ILPV's GI ms is its propagation, vpl's its selection,
# shadow maps and gather, caches' its stages, ldm's its maps, photons, split and splat.
while read -r scene; do
  csv=$out/sweep_$scene.csv
  vcsv=$out/vpl_$scene.csv
  ccsv=$out/caches_$scene.csv
  [ -f "$ccsv" ] || echo "scene,vals,selection,occlusion" > "$ccsv"
  lcsv=$out/ldm_$scene.csv
  gnuplot <<EOF
set datafile separator ","
set terminal pngcairo size 1000,700 font ",11"
set key outside right top
set grid
set logscale x
set xlabel "GI ms per frame (median): ILPV propagation, vpl selection + shadow maps + gather, caches stages, ldm all"
set ylabel "indirect relative RMSE vs the path-traced one-bounce image"
set logscale y
selt(t,b,m,l) = "< awk -F, 'NR>1 && \$26==\"" . t . "\" && \$2==\"" . b . "\" && \$3==\"" . m . "\" && (\"" . l . "\"==\"any\" || \$9==\"" . l . "\")' $csv"
sel(b,m,l) = selt("beams",b,m,l)
selp(b,m,l) = selt("paper",b,m,l)
front = "< awk -F, 'NR>1 && \$25==1' $csv | sort -t, -k11,11g"
vis(v) = "< awk -F, 'NR>1 && \$19==0 && \$28==\"flux\" && \$16==\"" . v . "\"' $vcsv"
rule(r) = "< awk -F, 'NR>1 && \$19==0 && \$28==\"" . r . "\"' $vcsv"
inter = "< awk -F, 'NR>1 && \$19>0' $vcsv"
cs(o) = "< awk -F, 'NR>1 && \$3==\"importance\" && \$4==\"" . o . "\"' $ccsv"
lightskin = "< awk -F, 'NR>1 && \$3==\"all\"' $ccsv"
set output "$out/speed_accuracy_$scene.png"
set title "$scene: speed against accuracy (labels: lattice/steps; fit = 32^3 cells shaped to the scene)"
plot front using 11:16 with lines lw 2 lc rgb "black" title "Pareto front", \
     sel("cpu","incremental","0") using 11:16 with points pt 7 ps 1.2 lc rgb "#999999" title "CPU ILPV lambda 0 (plain LPV)", \
     sel("cpu","incremental","0.5") using 11:16 with points pt 7 lc rgb "#2a9d8f" title "CPU ILPV lambda 0.5", \
     sel("cpu","incremental","0.8") using 11:16 with points pt 7 lc rgb "#e76f51" title "CPU ILPV lambda 0.8", \
     sel("cpu","incremental","0.9") using 11:16 with points pt 7 lc rgb "#9b2226" title "CPU ILPV lambda 0.9", \
     sel("cpu","classic","any") using 11:16 with points pt 5 lc rgb "#264653" title "CPU classic LPV (accumulated)", \
     sel("gl","incremental","0") using 11:16 with points pt 6 ps 1.2 lc rgb "#999999" title "GL ILPV lambda 0", \
     sel("gl","incremental","0.8") using 11:16 with points pt 6 lc rgb "#e76f51" title "GL ILPV lambda 0.8", \
     sel("gl","classic","any") using 11:16 with points pt 4 lc rgb "#264653" title "GL classic LPV", \
     selp("cpu","incremental","0") using 11:16 with points pt 1 ps 1.4 lc rgb "#999999" title "paper CPU lambda 0 (the thesis's plain LPV)", \
     selp("cpu","incremental","0.8") using 11:16 with points pt 1 ps 1.4 lc rgb "#e76f51" title "paper CPU lambda 0.8", \
     selp("cpu","incremental","0.9") using 11:16 with points pt 1 ps 1.4 lc rgb "#9b2226" title "paper CPU lambda 0.9", \
     selp("cpu","classic","any") using 11:16 with points pt 8 ps 1.2 lc rgb "#264653" title "paper CPU classic", \
     selp("gl","incremental","any") using 11:16 with points pt 10 ps 1.2 lc rgb "#457b9d" title "paper GL (all)", \
     vis("exact") using 7:9 with linespoints pt 9 ps 1.3 lc rgb "#6a4c93" title "vpl, exact maps (labels: VPLs)", \
     vis("ism") using 7:9 with points pt 11 ps 1.3 lc rgb "#1d7874" title "vpl, ISM pull-push (labels: VPLs/size/points)", \
     vis("ism-splat") using 7:9 with points pt 13 ps 1.3 lc rgb "#b5838d" title "vpl, ISM splats", \
     inter using 7:9 with points pt 3 ps 1.3 lc rgb "#d62828" title "vpl, interleaved (any maps)", \
     rule("view") using 7:9 with points pt 15 ps 1.3 lc rgb "#f4a261" title "vpl, view-importance selection (any maps)", \
     rule("regular") using 7:9 with points pt 2 ps 1.3 lc rgb "#6d6875" title "vpl, regular pattern (any maps)", \
     cs("approx") using 13:15 with linespoints pt 8 ps 1.3 lc rgb "#e9c46a" title "caches, disk occlusion (labels: VALs)", \
     cs("exact") using 13:15 with linespoints pt 10 ps 1.3 lc rgb "#bc6c25" title "caches, exact occlusion", \
     cs("off") using 13:15 with points pt 1 ps 1.3 lc rgb "#a3a380" title "caches, no occlusion", \
     lightskin using 13:15 with points pt 12 ps 1.5 lc rgb "#3a5a40" title "caches, every RSM texel (plain LightSkin)", \
     cs("approx") using 13:15:2 with labels offset 0,0.9 font ",8" notitle, \
     "< tail -n +2 $lcsv" using 9:12 with linespoints pt 8 ps 1.4 lc rgb "#0077b6" title "ldm (labels: maps/resolution)", \
     "< tail -n +2 $lcsv" using 9:12:(sprintf("%d/%d", \$2, \$3)) with labels offset 0,0.9 font ",8" notitle, \
     "< tail -n +2 $vcsv" using 7:9:((strcol(16) eq "exact" ? sprintf("%d", \$2) : sprintf("%d/%d/%d", \$2, \$17, \$18)) . (\$19 > 0 ? sprintf(" k%d", \$19) : "")) with labels offset 0,-0.9 font ",8" notitle, \
     front using 11:16:((\$4 == 0 ? "fit" : sprintf("%d", \$4)) . sprintf("/%d", \$8)) with labels offset 0,0.8 font ",8" notitle
set output "$out/frame_accuracy_$scene.png"
set xlabel "whole frame ms (frame pass + one eye pass, median)"
set title "$scene: whole-frame time against accuracy"
plot sel("cpu","incremental","0") using 14:16 with points pt 7 lc rgb "#999999" title "ILPV lambda 0", \
     sel("cpu","incremental","0.8") using 14:16 with points pt 7 lc rgb "#e76f51" title "ILPV lambda 0.8", \
     sel("cpu","incremental","0.9") using 14:16 with points pt 7 lc rgb "#9b2226" title "ILPV lambda 0.9", \
     sel("cpu","classic","any") using 14:16 with points pt 5 lc rgb "#264653" title "classic LPV", \
     sel("gl","incremental","any") using 14:16 with points pt 6 lc rgb "#457b9d" title "GL ILPV (all)", \
     selp("cpu","incremental","0") using 14:16 with points pt 1 ps 1.4 lc rgb "#999999" title "paper lambda 0", \
     selp("cpu","incremental","0.8") using 14:16 with points pt 1 ps 1.4 lc rgb "#e76f51" title "paper lambda 0.8", \
     selp("cpu","classic","any") using 14:16 with points pt 8 ps 1.2 lc rgb "#264653" title "paper classic", \
     vis("exact") using 8:9 with linespoints pt 9 ps 1.3 lc rgb "#6a4c93" title "vpl, exact maps", \
     vis("ism") using 8:9 with points pt 11 ps 1.3 lc rgb "#1d7874" title "vpl, ISM pull-push", \
     vis("ism-splat") using 8:9 with points pt 13 ps 1.3 lc rgb "#b5838d" title "vpl, ISM splats", \
     inter using 8:9 with points pt 3 ps 1.3 lc rgb "#d62828" title "vpl, interleaved (any maps)", \
     rule("view") using 8:9 with points pt 15 ps 1.3 lc rgb "#f4a261" title "vpl, view-importance selection", \
     rule("regular") using 8:9 with points pt 2 ps 1.3 lc rgb "#6d6875" title "vpl, regular pattern", \
     cs("approx") using 14:15 with linespoints pt 8 ps 1.3 lc rgb "#e9c46a" title "caches, disk occlusion", \
     cs("exact") using 14:15 with linespoints pt 10 ps 1.3 lc rgb "#bc6c25" title "caches, exact occlusion", \
     "< tail -n +2 $lcsv" using 10:12 with linespoints pt 8 ps 1.4 lc rgb "#0077b6" title "ldm"
set output "$out/ao_$scene.png"
set xlabel "ambient occlusion ms per eye (median)"
set ylabel "AO relative RMSE vs the path tracer's AO"
set title "$scene: layered depth maps against screen-space AO (labels: distance m; maps/resolution)"
ao(m,d) = "< awk -F, 'NR>1 && \$2==\"" . m . "\" && \$3==" . d . "' $out/ao_$scene.csv"
ds = "0.25 0.5 1 2"
plot for [i=1:4] ao("ssao", word(ds, i)) using 6:9 with points pt 6 ps 1.5 lc i title "ssao, ".word(ds, i)." m", \
     for [i=1:4] ao("ldm", word(ds, i)) using 6:9 with linespoints pt 7 lc i title "ldm, ".word(ds, i)." m", \
     "< awk -F, 'NR>1 && \$2==\"ldm\"' $out/ao_$scene.csv" using 6:9:(sprintf("%gm %d/%d", \$3, \$4, \$5)) with labels offset 0,-0.9 font ",7" notitle
unset logscale x
unset logscale y
set logscale x 2
set xlabel "propagation steps per frame"
set ylabel "MAE of the displayed image vs 32 plain steps"
set title "$scene: the paper's Fig. 2 (CPU, 32 cells along the longest axis), both transports"
lat = 32
sl(t,l) = "< awk -F, 'NR>1 && \$26==\"" . t . "\" && \$2==\"cpu\" && \$3==\"incremental\" && \$4==" . lat . " && \$9==\"" . l . "\"' $csv"
set output "$out/self32_$scene.png"
plot for [l in "0 0.5 0.8 0.9"] sl("beams",l) using 8:24 with linespoints pt 7 title "beams, lambda ".l, \
     for [l in "0 0.5 0.8 0.9"] sl("paper",l) using 8:24 with linespoints dt 2 pt 1 title "paper, lambda ".l
EOF
  gnuplot <<EOF
set datafile separator ","
set terminal pngcairo size 1000,600 font ",11"
set key outside right top
set grid
set output "$out/move_$scene.png"
set logscale y
set xlabel "frames after the light jumped"
set ylabel "relative summed |lattice - steady state after the move|"
set format y "10^{%L}"
set title "$scene: convergence after an abrupt light move (8 steps per frame)"
mv(m,l) = "< awk -F, 'NR>1 && \$1==\"" . m . "\" && \$2==\"" . l . "\"' $out/move_$scene.csv"
plot for [l in "0 0.5 0.8 0.9"] mv("incremental", l) using 3:(\$4>1e-7?\$4:1e-7) with linespoints pt 7 ps 0.6 title "ILPV lambda ".l, \
     mv("classic", "0") using 3:(\$4>1e-7?\$4:1e-7) with linespoints pt 5 ps 0.6 title "classic LPV"
unset logscale y
set format y "%g"
set output "$out/path_$scene.png"
set xlabel "frame (light circling at walking speed, 60 Hz)"
set ylabel "mean |image - previous image| / mean image"
set title "$scene: frame-to-frame change along a light path"
pa(m,l) = "< awk -F, 'NR>1 && \$1==\"" . m . "\" && \$2==\"" . l . "\"' $out/path_$scene.csv"
plot pa("incremental","0") using 3:6 with lines lw 2 lc rgb "black" title "direct light (the motion itself)", \
     for [l in "0 0.5 0.8 0.9"] pa("incremental", l) using 3:5 with lines title "indirect, ILPV lambda ".l, \
     pa("classic","0") using 3:5 with lines dt 2 title "indirect, classic LPV"
EOF
done < "$out/scenes.txt"

if [ $docs = 1 ]; then
  mkdir -p "$root/docs/accuracy"
  cp "$out"/*.png "$root/docs/accuracy/"
  python3 "$root/scripts/accuracy_report.py" "$out" $([ $quick = 1 ] && echo --quick) \
    > "$root/docs/ACCURACY.md"
  echo "chart: wrote docs/ACCURACY.md and docs/accuracy/*.png" >&2
fi
echo "chart: CSVs and charts in $out ($((SECONDS - start)) s)" >&2

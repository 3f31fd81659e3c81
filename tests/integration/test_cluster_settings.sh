#!/usr/bin/env bash
# Every GI setting reaches every node. Every method of the registry runs on 2 nodes. A
# 2-node cluster whose master is given GI settings
# on its command line renders each screen as a standalone node with the same options and
# that screen's view does (the same checksum, the same pixels), both nodes with equal
# checksums in every frame; first the vpl method's fastest chart rows (imperfect shadow
# maps, 4 x 4 interleaving), the caches method with 512 VALs, exact occlusion and glossy
# proxies (the head-derived viewer: both walls the same), ILPV with
# a fitted lattice, lambda and steps on either transport (--lpv-transport), the layered
# depth maps' indirect light with their ambient occlusion of an ambient term. The same
# settings from the config's "settings" give the same frames. --budget-ms measures every
# node and takes one choice for all. And the master refuses a bad value or name in one
# line, before any node starts.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/cluster_lib.sh"

SETTINGS='"rsm": 64' make_config "$tmp/c2.json" 30000 a b
# A still head at 1.7 m in the CAVE's centre, the wand behind it (no HUD in view).
{
  echo "cavelight-input 1"
  echo "head 0 0 1.7 0 1 0 0 0 1 0 0 0 1"
  echo "wand 0 0 1.7 2.5 1 0 0 0 1 0 0 0 1"
  for i in 0 1 2 3; do echo "poll $(python3 -c "print($i / 30)") 0.0333333333"; done
} > "$tmp/still.rec"
# The two node screens of make_config: front-l (node a) and front-r (node b).
screen_a="-1.5,0,-1.5,0,0,-1.5,-1.5,3,-1.5"
screen_b="0,0,-1.5,1.5,0,-1.5,0,3,-1.5"

# same_as_standalone NAME MASTER_OPTIONS...: the cluster run and one standalone run per
# screen with the same options; frame 3 of both compared.
same_as_standalone() {
  local name=$1
  shift
  "$build/cavelight-master" --config "$tmp/c2.json" --bind 'tcp://127.0.0.1:*' --spawn-local \
    --input "$tmp/still.rec" --output png --out "$tmp/$name" --report "$tmp/$name.json" \
    --node-args "$small_render" --quiet "$@" 2> "$tmp/$name.log" \
    || { cat "$tmp/$name.log"; fail "$name: master failed"; }
  [ "$(json 'r["frames"]' "$tmp/$name.json")" = 4 ] || fail "$name: not 4 frames"
  [ "$(json 'r["desyncs"]' "$tmp/$name.json")" = 0 ] || fail "$name: the nodes disagreed in a frame"
  [ "$(json 'len(set(n["last_checksum"] for n in r["per_node"]))' "$tmp/$name.json")" = 1 ] \
    || fail "$name: checksums differ"
  local cluster_sum
  cluster_sum=$(json 'r["per_node"][0]["last_checksum"]' "$tmp/$name.json")
  for node in a b; do
    local screen=screen_$node wall=front-l
    [ $node = b ] && wall=front-r
    "$build/cavelight-node" --standalone --frames 4 --width 32 --height 64 --threads 1 \
      --screen "${!screen}" --eye 0,1.7,0 --eyes stereo --rsm 64 --out "$tmp/$name-$node" \
      "$@" > "$tmp/$name-$node.log" || { cat "$tmp/$name-$node.log"; fail "$name: standalone failed"; }
    [ "$(json 'r["frames"][3]["checksum"]' "$tmp/$name-$node/report.json")" = "$cluster_sum" ] \
      || fail "$name: node $node's checksum is not the standalone node's"
    for eye in left right; do
      local mae
      mae=$("$build/cavelight-compare" "$tmp/$name/$wall-$eye.png" "$tmp/$name-$node/frame0003_$eye.png" \
            | python3 -c "import json,sys; print(json.load(sys.stdin)['mae'])")
      echo "$name: $wall $eye eye, cluster against standalone: mean absolute difference $mae"
      python3 -c "import sys; sys.exit(0 if float('$mae') == 0 else 1)" \
        || fail "$name: $wall $eye differs from the standalone node's image"
    done
  done
}

# Every method of the registry (the choices of --gi) on a 2-node cluster: both nodes on it,
# equal checksums in every frame.
methods=$("$build/cavelight-master" --help | sed -n 's/^  --gi \([a-z|]*\).*/\1/p' | tr '|' ' ')
[ -n "$methods" ] || fail "master --help lists no --gi methods"
for m in $methods; do
  "$build/cavelight-master" --config "$tmp/c2.json" --bind 'tcp://127.0.0.1:*' --spawn-local \
    --input "$tmp/still.rec" --output headless --report "$tmp/m-$m.json" --node-args "$small_render" \
    --quiet --gi "$m" --vpl-count 64 2> "$tmp/m-$m.log" || { cat "$tmp/m-$m.log"; fail "$m: master failed"; }
  [ "$(json 'r["desyncs"]' "$tmp/m-$m.json")" = 0 ] || fail "$m: the nodes disagreed in a frame"
  [ "$(json 'min(n["frames_ready"] for n in r["per_node"])' "$tmp/m-$m.json")" = 4 ] || fail "$m: a node missed frames"
  echo "--gi $m: 2 nodes, 4 frames, equal checksums"
done

same_as_standalone vpl --gi vpl --vpl-count 64 --vpl-visibility ism --vpl-interleave 4
same_as_standalone caches --gi caches --caches-vals 512 --caches-occlusion exact --caches-glossy on
same_as_standalone ilpv --gi ilpv --lattice-cells 4096 --lambda 0.5 --steps 4
# The thesis's transport: one value on every node, not the beams' frames.
same_as_standalone paper --gi ilpv --lpv-transport paper --lattice-cells 4096 --lambda 0.5 --steps 4
[ "$(json 'r["per_node"][0]["last_checksum"]' "$tmp/paper.json")" != \
  "$(json 'r["per_node"][0]["last_checksum"]' "$tmp/ilpv.json")" ] || fail "--lpv-transport paper gives beams' frames"
same_as_standalone ldm --gi ldm --ldm-directions 16 --ldm-resolution 64 --ldm-photons 8 \
  --ao ldm --ao-directions 16 --ao-resolution 64 --ambient 0.5

# The same ILPV settings from the config's "settings": the same frames.
SETTINGS='"rsm": 64, "gi": "ilpv", "lattice-cells": 4096, "lambda": 0.5, "steps": 4' \
  make_config "$tmp/c2.json" 30000 a b
"$build/cavelight-master" --config "$tmp/c2.json" --bind 'tcp://127.0.0.1:*' --spawn-local \
  --input "$tmp/still.rec" --output png --out "$tmp/config" --report "$tmp/config.json" \
  --node-args "$small_render" --quiet 2> "$tmp/config.log" || { cat "$tmp/config.log"; fail "config run failed"; }
[ "$(json 'r["per_node"][0]["last_checksum"]' "$tmp/config.json")" = \
  "$(json 'r["per_node"][0]["last_checksum"]' "$tmp/ilpv.json")" ] || fail "config settings differ from the options"
echo "the config's settings give the options' frames"

# --budget-ms: every node measures the candidate lattices, the slowest counts, and one
# choice serves the wall: the frames after the measuring ones are a standalone node's with
# the chosen lattice and steps.
SETTINGS='"rsm": 64' make_config "$tmp/c2.json" 30000 a b
"$build/cavelight-master" --config "$tmp/c2.json" --bind 'tcp://127.0.0.1:*' --spawn-local \
  --input "$tmp/still.rec" --output png --out "$tmp/budget" --report "$tmp/budget.json" \
  --node-args "$small_render" --budget-ms 20 2> "$tmp/budget.log" || { cat "$tmp/budget.log"; fail "budget: master failed"; }
grep -q "budget 20 ms: lattice [0-9]*, [0-9]* steps\?, predicted .* on the slowest node" "$tmp/budget.log" \
  || fail "budget: no choice said: $(cat "$tmp/budget.log")"
[ "$(json 'r["frames"] - r["budget"]["frames"], r["desyncs"], len(set(n["last_checksum"] for n in r["per_node"]))' \
     "$tmp/budget.json")" = "4 0 1" ] || fail "budget: not 4 frames with equal checksums after measuring"
lattice=$(json 'r["budget"]["lattice_cells"]' "$tmp/budget.json")
steps=$(json 'r["budget"]["steps"]' "$tmp/budget.json")
"$build/cavelight-node" --standalone --frames 4 --width 32 --height 64 --threads 1 --screen "$screen_a" \
  --eye 0,1.7,0 --eyes stereo --rsm 64 --lattice "$lattice" --steps "$steps" --out "$tmp/budget-a" > /dev/null \
  || fail "budget: standalone failed"
[ "$(json 'r["frames"][3]["checksum"]' "$tmp/budget-a/report.json")" = \
  "$(json 'r["per_node"][0]["last_checksum"]' "$tmp/budget.json")" ] || fail "budget: the wall did not take the choice"
echo "--budget-ms 20: lattice $lattice, $steps steps on both nodes, as a standalone node with those"

# Refused in one line naming the option and its range, or the setting and the nearest name.
one_line() { # WHAT EXPECTED ARGS...
  local what=$1 expect=$2 out
  shift 2
  out=$("$build/cavelight-master" --config "$tmp/c2.json" --spawn-local "$@" 2>&1) && fail "$what accepted"
  [ "$(wc -l <<< "$out")" = 1 ] || fail "$what: more than one line: $out"
  grep -qF -- "$expect" <<< "$out" || fail "$what: '$out' lacks '$expect'"
}
one_line "--vpl-interleave 9" "--vpl-interleave 9: expected a whole number in 0..8" --vpl-interleave 9
one_line "--ism-size 48" "--ism-size 48: expected a power of two in 8..256" --ism-size 48
one_line "--lpv-mode fast" "expected one of incremental or classic" --lpv-mode fast
one_line "--lambda 1.5" "--lambda 1.5: expected a number in [0, 0.999]" --lambda 1.5
one_line "--budget-ms with --lattice" "--budget-ms chooses --lattice: give either the budget or it" --budget-ms 10 --lattice 32
one_line "--budget-ms with vpl" "it needs --gi ilpv" --budget-ms 10 --gi vpl
SETTINGS='"vpl-cuont": 64' make_config "$tmp/bad.json" 30000 a b
out=$("$build/cavelight-master" --config "$tmp/bad.json" --spawn-local --out "$tmp/bad" 2>&1) \
  && fail "a misspelt setting accepted"
grep -qF "settings.vpl-cuont: 64: not a setting (did you mean vpl-count?)" <<< "$out" || fail "bad setting: $out"
[ ! -d "$tmp/bad/logs" ] || fail "nodes were started for a refused config"
echo "bad settings refused in one line before any node starts"

# Settings the nodes' limits would refuse (common/gi/gi_cost.h: over ten times the set-up
# work, or over limits.gi_memory_mb) are refused by the master before any node starts; set
# up in the config, the same settings pass.
out=$("$build/cavelight-master" --config "$tmp/c2.json" --spawn-local --out "$tmp/runaway" \
      --lattice 128 --steps 256 2>&1) && fail "a runaway lattice and steps accepted"
grep -qF "the ilpv settings would take" <<< "$out" && grep -qF "(at most 10): every node would refuse it" <<< "$out" \
  || fail "runaway: $out"
[ ! -d "$tmp/runaway/logs" ] || fail "nodes were started for runaway settings"
SETTINGS='"rsm": 64, "lattice": 64, "steps": 16' make_config "$tmp/heavy.json" 30000 a b
"$build/cavelight-master" --config "$tmp/heavy.json" --bind 'tcp://127.0.0.1:*' --spawn-local --render none \
  --frames 1 --out "$tmp/heavy" --quiet 2> "$tmp/heavy.log" || { cat "$tmp/heavy.log"; fail "set-up heavy settings refused"; }
echo "runaway settings refused before any node starts; the same set up in the config pass"

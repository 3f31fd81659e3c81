#!/usr/bin/env bash
# One argument style for every program (common/base/cli.h): --help exits 0 and prints
# every option with its default, grouped, on stdout; an unknown option names the closest
# valid one; an option of the other mode names the mode where it works; the hints name
# options that work in the mode used.
set -euo pipefail
build=$(cd "${1:?usage: $0 BUILD_DIR}" && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

for prog in cavelight-master cavelight-node cavelight-bench cavelight-compare; do
    "$build/$prog" --help > "$out/help" 2> "$out/err" || fail "$prog --help exited $?"
    [ ! -s "$out/err" ] || fail "$prog --help wrote to stderr: $(cat "$out/err")"
    grep -q "^usage: $prog" "$out/help" || fail "$prog --help has no usage line"
    grep -q "(default: " "$out/help" || fail "$prog --help shows no defaults"
    grep -q "^  --help, -h" "$out/help" || fail "$prog --help does not list --help"
    "$build/$prog" -h | cmp -s - "$out/help" || fail "$prog -h differs from --help"
    echo "$prog --help: $(grep -c '^  --' "$out/help") options"
done
# A subcommand's own help: the accuracy sweep's options (and the common ones) with defaults.
"$build/cavelight-bench" accuracy sweep --help > "$out/sweep" 2> "$out/err" || fail "accuracy sweep --help exited $?"
[ ! -s "$out/err" ] && grep -q "^usage: cavelight-bench accuracy sweep" "$out/sweep" &&
  grep -q "^  --lattices N,N" "$out/sweep" && grep -q "(default: 16,32,64,fit)" "$out/sweep" &&
  grep -q "^  --scene" "$out/sweep" \
  || fail "accuracy sweep --help: $(cat "$out/sweep" "$out/err")"
for e in move path savings; do
  "$build/cavelight-bench" accuracy $e --help > "$out/exp" 2> "$out/err" && [ ! -s "$out/err" ] &&
    grep -q "^usage: cavelight-bench accuracy $e" "$out/exp" && grep -q "^  --lattice N" "$out/exp" \
    || fail "accuracy $e --help: $(cat "$out/exp" "$out/err")"
done
# The groups the node and the master print.
"$build/cavelight-node" --help > "$out/node"
"$build/cavelight-master" --help > "$out/master"
for g in "Mode" "Cluster (--cluster)" "Scene and view" "Output" "GI: indirect light"; do
    grep -qF "$g" "$out/node" || fail "node --help lacks the group $g"
done
for g in "Cluster" "Nodes" "Output" "Input" "GI: indirect light" "Display"; do
    grep -q "^$g" "$out/master" || fail "master --help lacks the group $g"
done
# Every GI and display option of the node (its GI group and the settings of its display
# group) the master lists too, with the same argument: it sets them for every node.
options() { # the options of the group whose title starts with $2 in help file $1
    awk -v g="$2" '/^[^ ]/ { on = index($0, g) == 1 } on && /^  --/ { print $1, $2 }' "$1"
}
options "$out/node" "GI: indirect light" > "$out/node-gi"
options "$out/node" "Display" | grep -v -e "^--hud" -e "^--wand" >> "$out/node-gi"
[ "$(wc -l < "$out/node-gi")" -ge 20 ] || fail "the node lists only $(wc -l < "$out/node-gi") GI options"
{ options "$out/master" "GI: indirect light"; options "$out/master" "Display"; } > "$out/master-gi"
while read -r line; do
    case $line in --threads*) continue ;; esac # the node's own machine
    grep -qxF -- "$line" "$out/master-gi" || fail "master --help lacks the node's $line"
done < "$out/node-gi"
echo "the master lists all $(grep -vc -e '^--threads' "$out/node-gi") GI and display options of the node"

# Errors: exit 2, one line, naming what is wrong and what to use instead.
one_line_error() { # expected-substring command...
    local want=$1 rc=0; shift
    "$@" > "$out/stdout" 2> "$out/err" || rc=$?
    [ "$rc" -eq 2 ] || fail "$* exited $rc, expected 2"
    [ "$(wc -l < "$out/err")" -eq 1 ] || fail "$* gave more than one line: $(cat "$out/err")"
    grep -qF -- "$want" "$out/err" || fail "$* error lacks '$want': $(cat "$out/err")"
}
one_line_error "did you mean --frames?" "$build/cavelight-node" --standalone --frame 2
one_line_error "did you mean --lattice?" "$build/cavelight-node" --standalone --lattise 8
one_line_error "did you mean --standalone?" "$build/cavelight-node" -standalone
one_line_error "did you mean --spawn-local?" "$build/cavelight-master" --config x.json --spawn-locale
one_line_error "did you mean --mask-background?" "$build/cavelight-compare" a b --mask-backgrund
one_line_error "did you mean --iterations?" "$build/cavelight-bench" input --iteration 5
one_line_error "did you mean lpv?" "$build/cavelight-bench" lpx
one_line_error "--lambdas 0.5,1.5: expected 1..16 comma-separated numbers in 0..0.999" \
  "$build/cavelight-bench" accuracy sweep --lambdas 0.5,1.5
one_line_error "did you mean --lattices?" "$build/cavelight-bench" accuracy sweep --lattice 8
one_line_error "--distance -1: expected a positive number" "$build/cavelight-bench" accuracy move --distance -1
one_line_error "--gl works only in standalone mode" "$build/cavelight-node" --cluster x.json --name a --gl egl
one_line_error "--lattice works only in standalone mode" "$build/cavelight-node" --cluster x.json --name a --lattice 8
one_line_error "--vpl-count 5: expected a whole number in 64..4096" "$build/cavelight-master" --config x.json --vpl-count 5
one_line_error "--name works only in cluster mode" "$build/cavelight-node" --standalone --name a
one_line_error "--width needs a value" "$build/cavelight-node" --standalone --width
one_line_error "--frames 0: expected a whole number in 1..1000000" "$build/cavelight-node" --standalone --frames 0
one_line_error "--config FILE is required" "$build/cavelight-master" --frames 3
one_line_error "add --spawn-local or --spawn-remote" "$build/cavelight-master" --config x.json --output png

# The no-display hints name the option of the mode in use.
cat > "$out/c.json" <<'JSON'
{"master": {"bind": "tcp://127.0.0.1:1", "connect": "tcp://127.0.0.1:1"}, "security": {"mode": "insecure"},
 "screens": [{"name": "s", "bottom_left": [-1,0,-1], "bottom_right": [1,0,-1], "top_left": [-1,2,-1]}],
 "nodes": [{"name": "a", "screens": ["s"], "resolution": [8, 8], "output": "window"}]}
JSON
rc=0
env -u DISPLAY -u WAYLAND_DISPLAY "$build/cavelight-node" --standalone --gl glfw 2> "$out/err" > /dev/null || rc=$?
[ $rc -ne 0 ] && grep -qF -- "--gl egl" "$out/err" || fail "standalone no-display hint: $(cat "$out/err")"
rc=0
env -u DISPLAY -u WAYLAND_DISPLAY "$build/cavelight-node" --cluster "$out/c.json" --name a \
    2> "$out/err" > /dev/null || rc=$?
[ $rc -ne 0 ] && grep -qF -- "--output headless" "$out/err" || fail "cluster no-display hint: $(cat "$out/err")"
! grep -qF -- "--gl" "$out/err" || fail "cluster no-display hint names --gl, which cluster mode refuses"
echo "CLI: help, suggestions, mode checks and hints OK"

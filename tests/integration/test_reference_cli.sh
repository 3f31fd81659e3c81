#!/usr/bin/env bash
# cavelight-node --standalone --renderer reference: the averaged PFMs, the PNG and the JSON
# report with the noise estimates, at a small size; one-line errors for what it refuses.
set -euo pipefail
build=$1
node="$build/cavelight-node"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$node" --standalone --renderer reference --width 48 --height 36 --samples 4 --bounces 3 \
    --seed 9 --out "$out/ref" > "$out/log" || { cat "$out/log" >&2; fail "reference run failed"; }
for k in direct indirect1 indirect final1 final; do
    f="$out/ref/reference_$k.pfm"
    [ -s "$f" ] || fail "$f missing"
    head -c 2 "$f" | grep -q PF || fail "$f is not a colour PFM"
done
head -c 8 "$out/ref/reference.png" | od -An -tx1 | grep -q "89 50 4e 47" || fail "no PNG"
json="$out/ref/reference.json"
python3 - "$json" <<'PY' || fail "reference.json lacks settings or noise fields"
import json, sys
r = json.load(open(sys.argv[1]))
assert r["renderer"] == "reference" and r["samples_per_half"] == 4 and r["max_bounces"] == 3
assert r["seeds"] == [9, 10] and r["width"] == 48 and r["render_ms"] > 0
for k in ("indirect1", "indirect"):
    n = r["noise"][k]
    assert n["mae"] > 0 and n["mean"] > 0 and 0 < n["relative"] < 10, (k, n)
assert r["noise"]["direct"]["mae"] == 0  # exact, the same in both halves
PY
# Same seed, same images.
"$node" --standalone --renderer reference --width 48 --height 36 --samples 4 --bounces 3 \
    --seed 9 --threads 1 --out "$out/again" > /dev/null || fail "second run failed"
cmp -s "$out/ref/reference_final.pfm" "$out/again/reference_final.pfm" \
    || fail "same seed, different thread count: images differ"

one_line_error() { # expected-substring command...
    local want=$1; shift
    if "$@" > /dev/null 2> "$out/err"; then fail "$* succeeded"; fi
    [ "$(wc -l < "$out/err")" -eq 1 ] || { cat "$out/err" >&2; fail "$* gave more than one line"; }
    grep -q -- "$want" "$out/err" || { cat "$out/err" >&2; fail "$* error lacks '$want'"; }
}
one_line_error "--eyes mono" "$node" --standalone --renderer reference --eyes stereo
one_line_error "--renderer" "$node" --standalone --renderer vulkan
one_line_error "--samples" "$node" --standalone --renderer reference --samples 0
echo "reference CLI: all checks passed"

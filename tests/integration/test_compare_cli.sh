#!/usr/bin/env bash
# cavelight-compare end to end: PFM and PNG inputs, --mask-background, --crop and
# --ssim-range checked against an independent direct (non-separable) Python evaluation of
# the metric definitions, a black reference reported as no signal (exit 3 unless
# --allow-no-signal), --flip's known answers (LDR on PNGs, HDR on PFMs), and one-line exit-2
# errors naming the file at fault.
set -euo pipefail
build=$1
tool="$build/cavelight-compare"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
command -v python3 > /dev/null || { echo "python3 not installed: skipped"; exit 77; }

# Images: a smooth reference with a black (background) band, an image that is a noisy,
# dimmer copy, a third image of another size, and an 8-bit PNG pair.
python3 - "$out" <<'PY'
import math, struct, sys, zlib
d = sys.argv[1]
W, H = 24, 18
f32 = lambda v: struct.unpack('<f', struct.pack('<f', v))[0]
def write_pfm(path, w, h, px):
    with open(path, 'wb') as f:
        f.write(b'PF\n%d %d\n-1.0\n' % (w, h))
        for y in range(h - 1, -1, -1):
            for x in range(w):
                f.write(struct.pack('<3f', *px[y * w + x]))
def write_png(path, w, h, px):
    raw = b''.join(b'\0' + bytes(v for p in px[y * w:(y + 1) * w] for v in p) for y in range(h))
    chunk = lambda t, b: struct.pack('>I', len(b)) + t + b + struct.pack('>I', zlib.crc32(t + b))
    with open(path, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 2, 0, 0, 0))
                + chunk(b'IDAT', zlib.compress(raw)) + chunk(b'IEND', b''))
seed = 12345
def noise():
    global seed
    seed = (seed * 1103515245 + 12345) % 2**31
    return seed / 2**31 - 0.5
ref, img = [], []
for y in range(H):
    for x in range(W):
        if x < 4:
            r = (0.0, 0.0, 0.0)
        else:
            r = tuple(f32(0.5 + 0.4 * math.sin(0.5 * x + c) * math.cos(0.35 * y)) for c in range(3))
        ref.append(r)
        img.append(tuple(f32(0.8 * v + 0.05 * noise()) for v in r))
write_pfm(d + '/ref.pfm', W, H, ref)
write_pfm(d + '/img.pfm', W, H, img)
write_pfm(d + '/small.pfm', W - 1, H, ref[:(W - 1) * H])
pref = [tuple((x * 10 + y * 3 + 40 * c) % 256 for c in range(3)) for y in range(H) for x in range(W)]
pimg = [tuple(min(255, v + 20) for v in p) for p in pref]
write_png(d + '/ref.png', W, H, pref)
write_png(d + '/img.png', W, H, pimg)

def metrics(img, ref, w, h, mask=None, L=0.0, eps=1e-2):
    lum = lambda p: 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]
    cnt = [mask is None or mask[i] for i in range(w * h)]
    pairs = [(a, b) for i in range(w * h) if cnt[i] for a, b in zip(img[i], ref[i])]
    n = len(pairs)
    m = {'pixels': n // 3, 'nonfinite': 0}
    m['mae'] = sum(abs(a - b) for a, b in pairs) / n
    m['mean'] = sum(a for a, _ in pairs) / n
    m['reference_mean'] = sum(b for _, b in pairs) / n
    m['rmse_rel'] = math.sqrt(sum((a - b) ** 2 for a, b in pairs) / n) / m['reference_mean']
    m['relmse'] = sum((a - b) ** 2 / (b * b + eps) for a, b in pairs) / n
    s = sum(a * b for a, b in pairs) / sum(a * a for a, _ in pairs)
    m['best_scale'] = s
    m['mae_scaled'] = sum(abs(s * a - b) for a, b in pairs) / n
    L = L or max(lum(ref[i]) for i in range(w * h) if cnt[i])
    c1, c2 = (0.01 * L) ** 2, (0.03 * L) ** 2
    tot = 0.0
    for y in range(h):
        for x in range(w):
            if not cnt[y * w + x]:
                continue
            sw = sx = sy = sxx = syy = sxy = 0.0
            for v in range(max(0, y - 5), min(h, y + 6)):
                for u in range(max(0, x - 5), min(w, x + 6)):
                    if not cnt[v * w + u]:
                        continue
                    g = math.exp(-((u - x) ** 2 + (v - y) ** 2) / 4.5)
                    a, b = lum(img[v * w + u]), lum(ref[v * w + u])
                    sw += g; sx += g * a; sy += g * b
                    sxx += g * a * a; syy += g * b * b; sxy += g * a * b
            mx, my = sx / sw, sy / sw
            vx, vy, cxy = sxx / sw - mx * mx, syy / sw - my * my, sxy / sw - mx * my
            tot += (2 * mx * my + c1) * (2 * cxy + c2) / ((mx * mx + my * my + c1) * (vx + vy + c2))
    m['ssim'] = tot / m['pixels']
    return m

import json
def crop(px, x0, y0, cw, ch):
    return [px[(y0 + y) * W + x0 + x] for y in range(ch) for x in range(cw)]
exp = {
    'plain': metrics(img, ref, W, H),
    'mask': metrics(img, ref, W, H, mask=[any(p) for p in ref]),
    'crop': metrics(crop(img, 5, 2, 12, 9), crop(ref, 5, 2, 12, 9), 12, 9, L=2.0),
    'png': metrics([tuple(f32(v / 255) for v in p) for p in pimg], [tuple(f32(v / 255) for v in p) for p in pref], W, H),
}
json.dump(exp, open(d + '/expected.json', 'w'))
PY

check() { # case-name json-line width height
    python3 - "$out/expected.json" "$1" "$2" "$3" "$4" <<'PY' || fail "$1: metrics differ from the Python evaluation"
import json, sys
exp = json.load(open(sys.argv[1]))[sys.argv[2]]
got = json.loads(sys.argv[3])
assert got['width'] == int(sys.argv[4]) and got['height'] == int(sys.argv[5]), got
for k, v in exp.items():
    if abs(got[k] - v) > 1e-9 * max(1.0, abs(v)):
        sys.exit('%s: %s = %r, expected %r' % (sys.argv[2], k, got[k], v))
for k in ('image', 'reference'):
    assert got[k].endswith('.pfm') or got[k].endswith('.png'), got
PY
}

line=$("$tool" "$out/img.pfm" "$out/ref.pfm") || fail "plain compare exited non-zero"
[ "$(printf '%s\n' "$line" | wc -l)" -eq 1 ] || fail "output is not one line: $line"
check plain "$line" 24 18
line=$("$tool" "$out/img.pfm" "$out/ref.pfm" --mask-background) || fail "--mask-background failed"
check mask "$line" 24 18
line=$("$tool" "$out/img.pfm" "$out/ref.pfm" --crop 5,2,12,9 --ssim-range 2) || fail "--crop failed"
check crop "$line" 12 9
line=$("$tool" "$out/img.png" "$out/ref.png") || fail "PNG compare failed"
check png "$line" 24 18
line=$("$tool" "$out/ref.pfm" "$out/ref.pfm") || fail "self compare failed"
python3 -c 'import json,sys; m=json.loads(sys.argv[1]); assert m["mae"]==0 and abs(m["ssim"]-1)<1e-12, m' \
    "$line" || fail "an image against itself is not a perfect match: $line"

# No signal: a black reference (with a black image, or one that leaks light) is not a
# perfect match. Exit 3, one line naming the reference, null relative RMSE and SSIM, and
# "signal": false; --allow-no-signal prints the same and exits 0. --mask-background on a
# black reference would leave no pixel: every pixel is compared and no signal reported.
python3 - "$out" <<'PY'
import struct, sys
d = sys.argv[1]
W, H = 8, 6
def write_pfm(path, px):
    with open(path, 'wb') as f:
        f.write(b'PF\n%d %d\n-1.0\n' % (W, H))
        for p in px:
            f.write(struct.pack('<3f', *p))
write_pfm(d + '/black.pfm', [(0.0, 0.0, 0.0)] * (W * H))
write_pfm(d + '/leak.pfm', [(0.0, 0.0, 0.0)] * (W * H - 1) + [(0.48, 0.48, 0.48)])
PY
for img in black leak; do
    for mask in "" --mask-background; do
        rc=0
        "$tool" "$out/$img.pfm" "$out/black.pfm" $mask > "$out/stdout" 2> "$out/stderr" || rc=$?
        [ "$rc" -eq 3 ] || fail "$img against black $mask exited $rc, expected 3"
        [ "$(wc -l < "$out/stderr")" -eq 1 ] && grep -qF "no signal: reference $out/black.pfm" \
            "$out/stderr" || fail "$img against black: stderr is not the no-signal line: $(cat "$out/stderr")"
        python3 - "$(cat "$out/stdout")" "$img" <<'PY' || fail "$img against black: JSON wrong"
import json, sys
m = json.loads(sys.argv[1])
assert m['signal'] is False and m['rmse_rel'] is None and m['ssim'] is None, m
assert m['pixels'] == 48 and m['reference_mean'] == 0, m
assert abs(m['mae'] - (0.01 if sys.argv[2] == 'leak' else 0)) < 1e-7, m
PY
    done
    line=$("$tool" "$out/$img.pfm" "$out/black.pfm" --allow-no-signal 2> "$out/stderr") \
        || fail "--allow-no-signal exited non-zero"
    [ ! -s "$out/stderr" ] || fail "--allow-no-signal printed to stderr: $(cat "$out/stderr")"
    python3 -c 'import json,sys; m=json.loads(sys.argv[1]); assert m["signal"] is False and m["ssim"] is None, m' \
        "$line" || fail "--allow-no-signal JSON wrong: $line"
done
line=$("$tool" "$out/black.pfm" "$out/leak.pfm") || fail "a black image against a lit reference is signal"
python3 -c 'import json,sys; m=json.loads(sys.argv[1]); assert m["signal"] is True and abs(m["rmse_rel"] - 48 ** 0.5) < 1e-5, m' \
    "$line" || fail "black image against a lit reference: $line"

# --flip: the known answers of tests/unit/test_flip.c through the tool. Uniform black
# against white PNGs (LDR-FLIP: 0.967380, the colour term alone); an image against itself
# (PFM: HDR-FLIP, exactly 0); a uniform PFM against black: one exposure, 0.965188.
python3 - "$out" <<'PY'
import struct, sys, zlib
d = sys.argv[1]
W, H = 8, 6
def write_png(path, v):
    raw = b''.join(b'\0' + bytes([v] * (3 * W)) for _ in range(H))
    chunk = lambda t, b: struct.pack('>I', len(b)) + t + b + struct.pack('>I', zlib.crc32(t + b))
    with open(path, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', W, H, 8, 2, 0, 0, 0))
                + chunk(b'IDAT', zlib.compress(raw)) + chunk(b'IEND', b''))
write_png(d + '/white8.png', 255)
write_png(d + '/black8.png', 0)
with open(d + '/grey.pfm', 'wb') as f:
    f.write(b'PF\n%d %d\n-1.0\n' % (W, H) + struct.pack('<3f', 0.37, 0.37, 0.37) * (W * H))
PY
flip_check() { # json-line expression
    python3 -c 'import json,sys; m=json.loads(sys.argv[1]); assert eval(sys.argv[2]), m' "$1" "$2" ||
        fail "--flip: $2: $1"
}
line=$("$tool" "$out/black8.png" "$out/white8.png" --flip) || fail "--flip on PNGs failed"
flip_check "$line" 'abs(m["flip"] - 0.967380) < 1e-5 and m["flip_mode"] == "ldr" and abs(m["flip_ppd"] - 67.0206) < 1e-3'
line=$("$tool" "$out/black8.png" "$out/white8.png") || fail "compare without --flip failed"
flip_check "$line" '"flip" not in m'
line=$("$tool" "$out/img.pfm" "$out/img.pfm" --flip --ppd 30) || fail "--flip on PFMs failed"
flip_check "$line" 'm["flip"] == 0 and m["flip_mode"] == "hdr" and m["flip_ppd"] == 30'
line=$("$tool" "$out/black.pfm" "$out/grey.pfm" --flip) || fail "--flip on a uniform PFM failed"
flip_check "$line" 'abs(m["flip"] - 0.965188) < 1e-4 and m["flip_exposures"] == 1'
line=$("$tool" "$out/img.pfm" "$out/ref.pfm" --flip --mask-background) || fail "--flip with a mask failed"
flip_check "$line" '0 < m["flip"] < 1 and m["flip_exposures"] >= 2 and m["flip_start_exposure"] < m["flip_stop_exposure"]'

# Errors: exit 2 and one line on stderr that names the file at fault.
expect_error() { # substring command...
    local want=$1 rc=0
    shift
    "$@" > "$out/stdout" 2> "$out/stderr" || rc=$?
    [ "$rc" -eq 2 ] || fail "'$*' exited $rc, expected 2"
    [ "$(wc -l < "$out/stderr")" -eq 1 ] || fail "'$*' error is not one line: $(cat "$out/stderr")"
    grep -qF -- "$want" "$out/stderr" || fail "'$*' error does not mention $want: $(cat "$out/stderr")"
    [ ! -s "$out/stdout" ] || fail "'$*' printed to stdout on error"
}
expect_error "$out/missing.pfm" "$tool" "$out/missing.pfm" "$out/ref.pfm"
expect_error "reference $out/missing.png" "$tool" "$out/img.pfm" "$out/missing.png"
expect_error "image $out/small.pfm is 23x18" "$tool" "$out/small.pfm" "$out/ref.pfm"
expect_error "$out/expected.json: neither a PFM nor a PNG" "$tool" "$out/expected.json" "$out/ref.pfm"
printf 'PF\n24 18\n-1.0\n' > "$out/truncated.pfm"
expect_error "$out/truncated.pfm: truncated" "$tool" "$out/img.pfm" "$out/truncated.pfm"
expect_error "does not fit" "$tool" "$out/img.pfm" "$out/ref.pfm" --crop 20,0,5,5
expect_error "--ssim-range" "$tool" "$out/img.pfm" "$out/ref.pfm" --ssim-range x
expect_error "give two PNGs (LDR-FLIP) or two PFMs" "$tool" "$out/black.pfm" "$out/white8.png" --flip
expect_error "--ppd" "$tool" "$out/img.pfm" "$out/ref.pfm" --flip --ppd 0
echo "compare CLI OK"

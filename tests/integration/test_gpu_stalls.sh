#!/usr/bin/env bash
# Stalls per steady frame (issue 30): every GI method and AO stage traced with apitrace on
# llvmpipe, a few frames at a tiny size, no image file asked for. Between two "cavelight
# frame" markers (renderer_frame_pass()) it counts the calls that make the host wait for
# the GPU: glFinish, glReadPixels, glGetTexImage, glGetBufferSubData and read mappings;
# those inside the "cavelight image" group (the final image the node hands out) are
# allowed and counted apart. Frame 0 builds the maps and the shaders' first use: frames 1
# on are steady.
#
# KNOWN below lists, per case, the stalls still there: the expected failures. A stall not
# listed fails the test, and so does a listed one that is gone (shrink the list).
set -euo pipefail
build=$1
node="$build/cavelight-node"
command -v apitrace > /dev/null || { echo "SKIP: apitrace not installed (scripts/deps.sh)"; exit 77; }
# apitrace preloads its GL wrapper ahead of everything, which an ASan build refuses (the
# sanitizer's runtime must come first): the stalls are counted in the normal build.
if ldd "$node" | grep -q libasan; then echo "SKIP: apitrace cannot trace an ASan build"; exit 77; fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

cases=(
    "ilpv-beams|--gi ilpv --lpv gl --lpv-transport beams --lattice 8 --steps 2"
    "ilpv-paper|--gi ilpv --lpv gl --lpv-transport paper --lattice 8 --steps 2"
    "vpl-exact|--gi vpl --vpl-count 64 --vpl-visibility exact"
    "vpl-ism|--gi vpl --vpl-count 64 --vpl-visibility ism"
    "vpl-ism-splat|--gi vpl --vpl-count 64 --vpl-visibility ism-splat"
    "caches-approx|--gi caches --caches-occlusion approx"
    "ldm|--gi ldm --ldm-directions 16 --ldm-resolution 64"
    "ao-ldm|--gi none --ao ldm --ambient 0.5"
    "ao-ssao|--gi none --ao ssao --ambient 0.5"
)
for c in "${cases[@]}"; do
    name=${c%%|*}
    # shellcheck disable=SC2086
    apitrace trace --api egl -o "$out/$name.trace" "$node" --standalone --scene default --frames 4 \
        --width 32 --height 24 --rsm 32 --light-drift 0.01 ${c#*|} > "$out/$name.log" 2>&1 \
        || { cat "$out/$name.log"; echo "FAIL: $name: the node failed under apitrace"; exit 1; }
    apitrace dump --color=never "$out/$name.trace" > "$out/$name.dump"
done

python3 - "$out" "${cases[@]%%|*}" <<'EOF'
import re, sys
out, names = sys.argv[1], sys.argv[2:]
# The stalls left, per case: the expected failures. Remove a kind once it is gone.
KNOWN = {
    # ILPV injects and composes on the host: the RSMs and the volumes come back.
    "ilpv-beams": {"glReadPixels", "glGetTexImage"},
    "ilpv-paper": {"glReadPixels", "glGetTexImage"},
    # vpl selects and ldm makes photons on the host from the RSMs read back.
    "vpl-exact": {"glReadPixels"},
    "vpl-ism": {"glReadPixels"},
    "vpl-ism-splat": {"glReadPixels"},
    "ldm": {"glReadPixels"},
}
STALLS = ("glFinish", "glReadPixels", "glGetTexImage", "glGetTextureImage", "glGetBufferSubData",
          "glGetNamedBufferSubData")
call = re.compile(r"^\d+ (gl\w+)\((.*)\)")

def kind(fn, args):
    if fn in STALLS:
        return fn
    if fn in ("glMapBuffer", "glMapNamedBuffer") and re.search(r"GL_READ_(ONLY|WRITE)", args):
        return fn
    if fn in ("glMapBufferRange", "glMapNamedBufferRange") and "GL_MAP_READ_BIT" in args:
        return fn
    return None

failed = []
for name in names:
    frames, image_depth = [], 0
    for line in open(f"{out}/{name}.dump", errors="replace"):
        m = call.match(line)
        if not m:
            continue
        fn, args = m.groups()
        if fn == "glDebugMessageInsert" and '"cavelight frame"' in args:
            frames.append({"image": 0})
        elif fn == "glPushDebugGroup" and '"cavelight image"' in args:
            image_depth += 1
        elif fn == "glPopDebugGroup" and image_depth:
            image_depth -= 1
        elif frames and (k := kind(fn, args)):
            f = frames[-1]
            key = "image" if image_depth else k
            f[key] = f.get(key, 0) + 1
    if len(frames) < 3:
        failed.append(f"{name}: {len(frames)} frame markers in the trace, want 4")
        continue
    steady = frames[1:]
    seen = set()
    for i, f in enumerate(steady, 1):
        stalls = {k: v for k, v in f.items() if k != "image"}
        seen |= set(stalls)
        print(f"{name} frame {i}: stalls {stalls or 'none'} (image readback {f['image']}, allowed)")
    known = KNOWN.get(name, set())
    if seen - known:
        failed.append(f"{name}: new stalls {sorted(seen - known)}")
    if known - seen:
        failed.append(f"{name}: listed stalls gone {sorted(known - seen)}: remove them from KNOWN")
print("expected failures (stalls left, per case):")
for name in names:
    print(f"  {name}: {', '.join(sorted(KNOWN.get(name, set()))) or 'none'}")
for f in failed:
    print("FAIL:", f)
sys.exit(1 if failed else 0)
EOF

#!/usr/bin/env bash
# Each rule once (issue 33), read from the product sources (common/, node/, master/, tools/,
# libcavelight/): every raw malloc/calloc/realloc says why it is not xalloc (xalloc.h's
# policy) in a "not xalloc:" comment on its line or just above; no function runs over 80
# lines (column-0 braces, the project's style); FNV-1a's prime and the double 4x4 product's
# loop appear only in common/base/fnv1a.h and common/base/mat4.c.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
python3 - "$root" <<'PY'
import os, re, sys
root = sys.argv[1]
dirs = ["common", "node", "master", "tools", "libcavelight"]
raw = re.compile(r"\b(malloc|calloc|realloc)\s*\(")
fnv = re.compile(r"0x100000001b3|1099511628211", re.I)
mul = re.compile(r"\[k \* 4 \+ \w+\]\s*\*.*\[c \* 4 \+ k\]")
faults = []
for d in dirs:
    for dp, _, names in os.walk(os.path.join(root, d)):
        for n in sorted(names):
            if not n.endswith((".c", ".cpp", ".h")):
                continue
            path = os.path.join(dp, n)
            rel = os.path.relpath(path, root)
            lines = open(path, errors="replace").read().split("\n")
            for i, line in enumerate(lines):
                code = line.split("//")[0].strip()
                if code.startswith(("/*", "*")):
                    continue
                if raw.search(code) and rel != "common/base/xalloc.c":
                    if not any("not xalloc:" in l for l in lines[max(0, i - 8):i + 1]):
                        faults.append(f"{rel}:{i + 1}: raw allocation without a 'not xalloc:' reason")
                if fnv.search(code) and rel != "common/base/fnv1a.h":
                    faults.append(f"{rel}:{i + 1}: FNV-1a written inline (use base/fnv1a.h)")
                if mul.search(code) and rel != "common/base/mat4.c":
                    faults.append(f"{rel}:{i + 1}: a 4x4 product written inline (use base/mat4.h)")
            i = 0
            while i < len(lines):
                if lines[i].startswith("{"):
                    j = i - 1  # the signature's first line
                    while j > 0 and lines[j - 1].strip() and not lines[j - 1].rstrip().endswith((";", "}", "*/")) \
                            and not lines[j - 1].startswith(("#", "//", " *", "/*")):
                        j -= 1
                    k = i + 1
                    while k < len(lines) and not lines[k].startswith("}"):
                        k += 1
                    if k - j + 1 > 80:
                        faults.append(f"{rel}:{j + 1}: function of {k - j + 1} lines (at most 80)")
                    i = k
                i += 1
for f in faults:
    print("FAIL:", f)
sys.exit(1 if faults else 0)
PY
echo "product rules: ok"

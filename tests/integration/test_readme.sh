#!/usr/bin/env bash
# Every command in README.md's shell blocks runs as written from a fresh clone: each runs
# in a scratch folder that holds the repository's files (links to them) and build/
# pointing at the built tree, with nothing under out/. Each must exit 0 and write what it
# says: a command with --out DIR leaves files in DIR (images, PFMs, reports), a benchmark
# or a comparison prints one JSON line. The two top-level scripts (scripts/demo.sh, scripts/test.sh) are
# left out: they install packages and rebuild, and CI runs them. No override: a README
# command too slow for this test is a README defect (make the command faster).
set -euo pipefail
build=$(cd "${1:?usage: $0 BUILD_DIR}" && pwd)
root=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# The commands: lines of ```sh blocks, continuation lines joined.
python3 - "$root/README.md" > "$tmp/commands" <<'PY'
import sys
block, cmd = False, ""
for line in open(sys.argv[1]):
    line = line.rstrip("\n")
    if line.startswith("```"):
        block = line.strip() in ("```sh", "```bash") and not block
        continue
    if not block or not line.strip():
        continue
    cmd += line.rstrip("\\").strip() + " " if line.endswith("\\") else line.strip()
    if not line.endswith("\\"):
        if not cmd.startswith("scripts/"):
            print(cmd)
        cmd = ""
PY
count=$(wc -l < "$tmp/commands")
[ "$count" -ge 9 ] || fail "only $count commands found in README.md's shell blocks"

clone="$tmp/clone"
mkdir "$clone"
for f in "$root"/* "$root"/.[!.]*; do
    name=$(basename "$f")
    case "$name" in build|out|.git) continue ;; esac
    ln -s "$f" "$clone/$name"
done
ln -s "$build" "$clone/build"

# The README's cluster command binds its config's fixed port: two suites on one machine
# (a CI run beside a developer's) would fail each other's run, so they take turns here.
exec 9> /tmp/cavelight-readme.lock
flock 9
n=0
while IFS= read -r cmd; do
    n=$((n + 1))
    start=$(date +%s)
    rc=0
    (cd "$clone" && bash -c "$cmd") > "$tmp/stdout" 2> "$tmp/stderr" < /dev/null || rc=$?
    [ "$rc" -eq 0 ] || { tail -20 "$tmp/stderr"; fail "exit $rc: $cmd"; }
    what=""
    if [[ " $cmd " =~ \ --out\ ([^ ]+) ]]; then
        dir="$clone/${BASH_REMATCH[1]}"
        files=$(find "$dir" -type f -size +0 \( -name '*.png' -o -name '*.pfm' -o -name '*.json' \) 2>/dev/null | wc -l)
        [ "$files" -gt 0 ] || fail "wrote no image or report into ${BASH_REMATCH[1]}: $cmd"
        what="$files files in ${BASH_REMATCH[1]}"
    elif [[ "$cmd" == build/cavelight-bench* || "$cmd" == build/cavelight-compare* ]]; then
        python3 -c 'import json, sys; [json.loads(l) for l in sys.stdin if l.strip()]' < "$tmp/stdout" \
            && [ "$(grep -c . "$tmp/stdout")" -eq 1 ] || fail "no single JSON line on stdout: $cmd"
        what="one JSON line"
    else
        fail "no check for: $cmd (add one here)"
    fi
    echo "README command $n ($(( $(date +%s) - start )) s, $what): $cmd"
done < "$tmp/commands"
echo "README: $n commands run as written, each exited 0 and wrote its output"

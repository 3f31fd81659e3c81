#!/usr/bin/env bash
# The rooms of the tree (scripts/check_layout.py): no GI method folder includes another
# method's header, master/ includes nothing of node/, common/ nothing of node/ or master/.
# Checked on the tree, then on copies with one wall broken each, which must be caught.
set -euo pipefail
src=$(cd "$(dirname "$0")/../.." && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
command -v python3 > /dev/null || { echo "python3 not installed: skipped"; exit 77; }

python3 "$src/scripts/check_layout.py" "$src" || fail "the tree crosses a wall (above)"

# broken NAME FILE INCLUDE EXPECTED: a copy of the tree with FILE including INCLUDE must
# fail with EXPECTED in the report.
broken() {
    local copy="$out/$1"
    mkdir -p "$copy"
    cp -r "$src/common" "$src/node" "$src/master" "$src/include" "$copy/"
    printf '#include "%s"\n' "$3" >> "$copy/$2"
    if python3 "$src/scripts/check_layout.py" "$copy" > "$copy.log"; then
        fail "$1: not caught"
    fi
    grep -q "$4" "$copy.log" || { cat "$copy.log"; fail "$1: no line naming $4"; }
}
broken method common/gi/caches/cache_grid.c gi/vpl/vpl_select.h \
    'common/gi/caches/cache_grid.c: includes "gi/vpl/vpl_select.h", a header of another method'
broken method-gl node/gi/ldm/gi_ldm.c gi/ilpv/lpv_converge.h \
    'node/gi/ldm/gi_ldm.c: includes "gi/ilpv/lpv_converge.h"'
broken master master/grab.c gl/gltools.h 'master/grab.c: includes "gl/gltools.h", which is under node/'
broken master-gi master/session.c gi/gi.h 'master/session.c: includes "gi/gi.h", which is under node/'
broken common common/frame/hud.c renderer.h 'common/frame/hud.c: includes "renderer.h", which is under node/'
echo "layout: the tree passes; 5 broken copies caught"

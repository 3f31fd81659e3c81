#!/usr/bin/env bash
# Invalid cluster configs: master and node each exit non-zero with one line that names the
# file and the field. Also an unknown node name and a missing file.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/cluster_lib.sh"

make_config "$tmp/good.json" 1000 a
check() { # FILE FIELD: both programs must refuse it with one line naming file and field
  local file=$1 field=$2
  for prog in master node; do
    local args=(--config "$file"); [ $prog = node ] && args=(--cluster "$file" --name a --render none)
    if "$build/cavelight-$prog" "${args[@]}" 2> "$tmp/err" >/dev/null; then fail "$prog accepted $file"; fi
    [ "$(wc -l < "$tmp/err")" = 1 ] || { cat "$tmp/err"; fail "$prog: not exactly one line for $file"; }
    grep -qF "$file" "$tmp/err" || fail "$prog: error does not name $file: $(cat "$tmp/err")"
    grep -qF "$field" "$tmp/err" || fail "$prog: error does not name field $field: $(cat "$tmp/err")"
  done
  echo "refused ($field): $(cat "$tmp/err")"
}
edit() { # NAME PYTHON: a copy of good.json changed by a Python statement on c
  python3 - "$tmp/good.json" "$tmp/$1.json" "$2" <<'PY'
import json, sys
c = json.load(open(sys.argv[1])); exec(sys.argv[3]); json.dump(c, open(sys.argv[2], "w"))
PY
}
printf '{"master": {"bind": "tcp://127.0.0.1:1",\n "connect": }' > "$tmp/syntax.json"; check "$tmp/syntax.json" "line 2"
edit noscreen 'c["nodes"][0]["screens"] = ["nowhere"]'; check "$tmp/noscreen.json" "nodes[0].screens[0]"
edit badres 'c["nodes"][0]["resolution"] = [0, 10]'; check "$tmp/badres.json" "nodes[0].resolution"
edit badeyes 'c["nodes"][0]["eyes"] = "both"'; check "$tmp/badeyes.json" "nodes[0].eyes"
edit skew 'c["screens"][0]["top_left"] = [-1, 3, -1.5]'; check "$tmp/skew.json" "screens[0]"
edit nomaster 'del c["master"]'; check "$tmp/nomaster.json" "master"
edit sep 'c["observer"]["eye_separation"] = -1'; check "$tmp/sep.json" "observer.eye_separation"
edit timeout 'c["timeouts"]["barrier_ms"] = "soon"'; check "$tmp/timeout.json" "timeouts.barrier_ms"

if "$build/cavelight-master" --config "$tmp/missing.json" 2> "$tmp/err"; then fail "missing file accepted"; fi
grep -qF "$tmp/missing.json" "$tmp/err" || fail "missing file not named"
if "$build/cavelight-node" --cluster "$tmp/good.json" --name zz --render none 2> "$tmp/err"; then fail "unknown node accepted"; fi
grep -q "no node named 'zz'" "$tmp/err" || fail "unknown node not named: $(cat "$tmp/err")"
echo "all invalid configs refused"

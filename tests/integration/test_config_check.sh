#!/usr/bin/env bash
# cavelight-master --check validates a config without starting anything: one line per
# problem (unknown keys with the nearest valid one, the scene, hosts, CURVE keys, --input),
# exit 2; exit 0 and "ok" for a good config, even while another process holds its port.
# A normal run warns about unknown keys and goes on; --strict refuses them before any
# node starts. Input configs' unknown keys are warned the same way.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/cluster_lib.sh"
master=$build/cavelight-master

make_config "$tmp/good.json" 5000 a b
# A port that is taken: a check that bound it would fail.
python3 - "$tmp/good.json" "$tmp/port" <<'PY' &
import json, socket, sys, time
s = socket.socket(); s.bind(("127.0.0.1", 0)); s.listen(1)
c = json.load(open(sys.argv[1])); port = s.getsockname()[1]
c["master"]["bind"] = c["master"]["connect"] = "tcp://127.0.0.1:%d" % port
json.dump(c, open(sys.argv[1], "w")); open(sys.argv[2], "w").write(str(port))
time.sleep(60)
PY
pids+=($!)
wait_for_file "$tmp/port" 10
mkdir "$tmp/cwd"
(cd "$tmp/cwd" && "$master" --config "$tmp/good.json" --check) 2> "$tmp/good.log" \
  || { cat "$tmp/good.log"; fail "a good config failed --check"; }
grep -q "check: $tmp/good.json: ok (5 screens, every key known, GI ilpv, scene default (38 triangles), 2 nodes on 1 hosts" \
  "$tmp/good.log" || fail "no ok line: $(cat "$tmp/good.log")"
[ -z "$(ls -A "$tmp/cwd")" ] || fail "--check wrote output: $(ls "$tmp/cwd")"

# Misspelt keys, a missing scene, a host that does not resolve: one line each, exit 2.
python3 - "$tmp/good.json" "$tmp/bad.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c["nodes"][0]["resolutoin"] = c["nodes"][0].pop("resolution")
c["nodes"][0]["resolution"] = [32, 64]
c["scren"] = []
c["scene"] = "no-such-scene.gltf"
c["nodes"][1]["host"] = "no-such-host.invalid"
c["settings"] = {"vpl-cuont": 64}
json.dump(c, open(sys.argv[2], "w"))
PY
rc=0; "$master" --config "$tmp/bad.json" --check 2> "$tmp/bad.log" || rc=$?
[ $rc = 2 ] || { cat "$tmp/bad.log"; fail "--check of a bad config exited $rc, not 2"; }
grep -q "field nodes\[0\].resolutoin: unknown key \"resolutoin\" (did you mean \"resolution\"?)" "$tmp/bad.log" \
  || fail "no resolutoin line: $(cat "$tmp/bad.log")"
grep -q "field scren: unknown key \"scren\" (did you mean \"screens\"?)" "$tmp/bad.log" || fail "no scren line"
grep -q "no-such-scene.gltf" "$tmp/bad.log" || fail "the missing scene is not named"
grep -q "field nodes\[1\].host: 'no-such-host.invalid' does not resolve" "$tmp/bad.log" || fail "the host is not named"
grep -q "settings.vpl-cuont: 64: not a setting (did you mean vpl-count?)" "$tmp/bad.log" || fail "the setting is not named"
[ "$(grep -c "check: " "$tmp/bad.log")" = 6 ] && grep -q "bad.json: 5 problems" "$tmp/bad.log" \
  || fail "not one line per problem: $(cat "$tmp/bad.log")"
echo "--check: a good config ok with its port taken; 5 problems in 5 lines, exit 2"
# AO without an ambient term: refused before anything starts, naming --ambient.
rc=0; "$master" --config "$tmp/good.json" --check --ao ssao 2> "$tmp/ao.log" || rc=$?
[ $rc = 2 ] && grep -q -- "--ambient" "$tmp/ao.log" || fail "--ao without --ambient: rc $rc, $(cat "$tmp/ao.log")"
python3 -c 'import json, sys; c = json.load(open(sys.argv[1])); del c["settings"]; json.dump(c, open(sys.argv[1], "w"))' \
  "$tmp/bad.json" # the sessions below run on its unknown keys, which a bad setting would stop

# CURVE keys: named when missing, ok after --keygen.
CLUSTER_SECURITY=curve make_config "$tmp/curve.json" 5000 a
rc=0; "$master" --config "$tmp/curve.json" --check 2> "$tmp/curve.log" || rc=$?
[ $rc = 2 ] && grep -q "master.key.*--keygen" "$tmp/curve.log" || fail "missing keys: rc $rc, $(cat "$tmp/curve.log")"
"$master" --config "$tmp/curve.json" --keygen 2> /dev/null
"$master" --config "$tmp/curve.json" --check 2> "$tmp/curve.log" || fail "keys made, still: $(cat "$tmp/curve.log")"

# An input config: unknown keys warned, its sources not opened (a DTrack port that is taken).
port=$(cat "$tmp/port")
cat > "$tmp/input.json" <<JSON
{"sources": [{"type": "dtrack", "prot": 1, "port": $port, "head": 1},
             {"type": "playback", "file": "$tmp/none.txt", "lop": true}]}
JSON
rc=0; "$master" --config "$tmp/good.json" --check --input "$tmp/input.json" 2> "$tmp/in.log" || rc=$?
[ $rc = 2 ] || { cat "$tmp/in.log"; fail "--check --input exited $rc"; }
grep -q "field sources\[0\].prot: unknown key \"prot\" (did you mean \"port\"?)" "$tmp/in.log" &&
  grep -q "field sources\[1\].lop: unknown key \"lop\" (did you mean \"loop\"?)" "$tmp/in.log" \
  || fail "input keys: $(cat "$tmp/in.log")"
echo "--check --input: unknown keys named, no source opened"

# A session: warnings and on; --strict: refused before any node starts.
"$master" --config "$tmp/bad.json" --bind 'tcp://127.0.0.1:*' --scene default --render none --spawn-local \
  --frames 2 --out "$tmp/run" 2> "$tmp/run.log" || { cat "$tmp/run.log"; fail "the session with unknown keys failed"; }
grep -q "warning: cluster config .*resolutoin" "$tmp/run.log" || fail "no warning: $(cat "$tmp/run.log")"
rc=0; "$master" --config "$tmp/bad.json" --bind 'tcp://127.0.0.1:*' --scene default --render none --spawn-local \
  --frames 2 --strict --out "$tmp/strict" 2> "$tmp/strict.log" || rc=$?
[ $rc = 1 ] && grep -q "2 unknown keys in .*bad.json: refused (--strict)" "$tmp/strict.log" \
  || fail "--strict: rc $rc, $(cat "$tmp/strict.log")"
[ ! -e "$tmp/strict/logs" ] || fail "--strict started nodes"
"$master" --config "$tmp/good.json" --bind 'tcp://127.0.0.1:*' --render none --spawn-local --frames 2 \
  --input "$tmp/input.json" --strict --quiet --out "$tmp/strict_in" 2> "$tmp/strict_in.log" && fail "--strict took the input config"
[ "$(wc -l < "$tmp/strict_in.log")" = 1 ] && grep -q "sources\[0\].prot: unknown key \"prot\" (did you mean \"port\"?) (and 1 more unknown keys)" \
  "$tmp/strict_in.log" || fail "--strict input config: $(cat "$tmp/strict_in.log")"
echo "unknown keys: warned in a session, refused with --strict"

# Projector warps, read as the nodes read them at start: the blended powerwall's MPCDI file
# passes; the same config beside a damaged copy is one problem naming the node and the file.
cfg=$(cd "$here/../../configs/clusters" && pwd)/powerwall-blend-local.json
"$master" --config "$cfg" --check 2> "$tmp/pw.log" && grep -q "ok (.*2 projector warps" "$tmp/pw.log" \
  || fail "the powerwall's warps: $(cat "$tmp/pw.log")"
cp "$cfg" "$tmp/pw.json"
head -c 100 "$(dirname "$cfg")/powerwall-blend.mpcdi" > "$tmp/powerwall-blend.mpcdi"
rc=0; "$master" --config "$tmp/pw.json" --check 2> "$tmp/pwbad.log" || rc=$?
[ $rc = 2 ] && [ "$(grep -c "^cavelight-master: check: node .*powerwall-blend.mpcdi" "$tmp/pwbad.log")" = 2 ] \
  || fail "a damaged MPCDI file: rc $rc, $(cat "$tmp/pwbad.log")"
echo "--check reads every projector warp: ok, and a damaged MPCDI file named per node"

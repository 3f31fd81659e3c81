#!/usr/bin/env bash
# scripts/install_nodes.py stages, per host, the node program as `cmake --install` lays it
# out, the config, the config's scene file with the files it names (at the path each node
# opens it), that host's own keys (never another host's private key), the systemd unit
# template and a drop-in per node with the node's program, folder, config and display;
# --dry-run prints the ssh and scp commands. The unit passes systemd-analyze verify where
# systemd is there to ask.
here=$(cd "$(dirname "$0")" && pwd)
. "$here/cluster_lib.sh"
root=$(cd "$here/../.." && pwd)

CLUSTER_SECURITY=curve make_config "$tmp/cave.json" 2000 a b c
# A scene beside the working folder, with a buffer and an image in files of their own.
mkdir -p "$tmp/scenes/tex"
echo '{"asset": {"version": "2.0"}, "buffers": [{"uri": "s.bin", "byteLength": 4}], "images": [{"uri": "tex/w%20a.png"}]}' \
  > "$tmp/scenes/s.gltf"
printf 'abcd' > "$tmp/scenes/s.bin"
printf 'png' > "$tmp/scenes/tex/w a.png"
python3 - "$tmp/cave.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c["scene"] = "scenes/s.gltf"
c["nodes"][0]["host"] = c["nodes"][1]["host"] = "render1"
c["nodes"][2].update({"host": "render2", "exe": "/usr/local/bin/cavelight-node", "workdir": "/srv/cave",
                      "config": "/srv/cave/cave.json", "display": ":1"})
json.dump(c, open(sys.argv[1], "w"))
PY
"$build/cavelight-master" --config "$tmp/cave.json" --keygen 2> /dev/null || fail "keygen failed"
(cd "$tmp" && python3 "$root/scripts/install_nodes.py" "$tmp/cave.json" --build "$build" --dry-run \
  --stage "$tmp/stage" --user cave) > "$tmp/out.txt" || { cat "$tmp/out.txt"; fail "install_nodes failed"; }
grep -q "staged 3 nodes on 2 hosts" "$tmp/out.txt" || fail "not 3 nodes on 2 hosts: $(cat "$tmp/out.txt")"
[ "$(grep -c "^ssh render1 " "$tmp/out.txt")" = 2 ] && grep -q "^scp -r .* render2:/tmp/cavelight-install/" "$tmp/out.txt" \
  || fail "ssh/scp commands: $(cat "$tmp/out.txt")"
s1=$tmp/stage/render1 s2=$tmp/stage/render2
[ -x "$s1/prefix/bin/cavelight-node" ] && [ -f "$s1/prefix/share/cavelight/shaders/shade.frag" ] \
  || fail "the program or its shaders were not staged as cmake --install lays them out"
grep -qx "cp -R prefix/. /opt/cavelight/" "$s1/install.sh" || fail "the staged prefix is not installed"
cmp -s "$s2/scene/s.bin" "$tmp/scenes/s.bin" && [ -f "$s2/scene/tex/w a.png" ] && [ -f "$s2/scene/s.gltf" ] \
  || fail "the scene and the files it names were not staged: $(cd "$s2" && find scene)"
grep -q "install -D -m 644 'scene/tex/w a.png' '/srv/cave/scenes/tex/w a.png'" "$s2/install.sh" &&
  grep -q "install -D -m 644 scene/s.gltf /home/cave/scenes/s.gltf" "$s1/install.sh" \
  || { cat "$s1/install.sh" "$s2/install.sh"; fail "the scene does not go where each node opens it"; }
for f in a.key a.pub b.key b.pub master.pub; do [ -f "$s1/keys/$f" ] || fail "render1 lacks $f"; done
[ ! -e "$s1/keys/c.key" ] && [ ! -e "$s2/keys/a.key" ] && [ ! -e "$s2/keys/b.key" ] \
  || fail "a host got another host's private key"
[ ! -e "$tmp/stage/render1/keys/master.key" ] && [ ! -e "$s2/keys/master.key" ] || fail "the master's private key was staged"
grep -qx "ExecStart=/usr/local/bin/cavelight-node --cluster /srv/cave/cave.json --name c" "$s2/dropins/c.conf" \
  && grep -qx "WorkingDirectory=/srv/cave" "$s2/dropins/c.conf" && grep -qx "Environment=DISPLAY=:1" "$s2/dropins/c.conf" \
  || { cat "$s2/dropins/c.conf"; fail "node c's drop-in"; }
grep -qx "ExecStart=/opt/cavelight/bin/cavelight-node --cluster /etc/cavelight/cave.json --name a" "$s1/dropins/a.conf" \
  || { cat "$s1/dropins/a.conf"; fail "node a's drop-in"; }
grep -q "install -m 600 -o cave keys/c.key /srv/cave/cave.keys/c.key" "$s2/install.sh" \
  || { cat "$s2/install.sh"; fail "node c's key does not go beside its config"; }
grep -q "systemctl enable cavelight-node@c" "$s2/install.sh" || fail "node c is not enabled"
! grep -q "@[A-Z]*@" "$s1/cavelight-node@.service" || fail "unfilled fields in the unit"
sh -n "$s1/install.sh" || fail "install.sh is not valid sh"
if systemd-analyze --version > /dev/null 2>&1; then
  sed "s|^ExecStart=.*|ExecStart=/bin/true %i|; s|^User=.*|User=root|" "$s1/cavelight-node@.service" \
    > "$tmp/cavelight-node@a.service"
  if systemd-analyze verify "$tmp/cavelight-node@a.service" > "$tmp/verify.txt" 2>&1; then
    echo "systemd-analyze verify: the unit is valid"
  elif grep -q "System has not been booted with systemd\|Failed to connect\|Failed to initialize" "$tmp/verify.txt"; then
    echo "systemd-analyze cannot run here: $(head -1 "$tmp/verify.txt")"
  else
    cat "$tmp/verify.txt"; fail "systemd-analyze verify refused the unit"
  fi
fi
# Refusals: a scene file that is not there, no keys yet, no build.
rm "$tmp/scenes/s.bin"
(cd "$tmp" && python3 "$root/scripts/install_nodes.py" "$tmp/cave.json" --build "$build" --dry-run) 2> "$tmp/err" \
  > /dev/null && fail "staged a scene whose buffer is missing"
grep -q "scene scenes/s.gltf: scenes/s.bin is missing" "$tmp/err" || fail "no line for the missing buffer: $(cat "$tmp/err")"
rm -r "$tmp/cave.keys"
python3 "$root/scripts/install_nodes.py" "$tmp/cave.json" --build "$build" --dry-run 2> "$tmp/err" > /dev/null \
  && fail "installed without keys"
grep -q "run cavelight-master --config .* --keygen first" "$tmp/err" || fail "no keygen hint: $(cat "$tmp/err")"
echo "install_nodes: staged per host, keys kept apart, drop-ins per node"

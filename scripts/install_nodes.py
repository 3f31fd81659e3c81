#!/usr/bin/env python3
"""Installs the render nodes of a cluster config as systemd services (docs/deploy.md).

Usage: scripts/install_nodes.py CONFIG [options]

For every host in CONFIG's "nodes" it stages, then copies over ssh and installs:
  the render node as `cmake --install BUILD --component node` lays it out under PREFIX
  (PREFIX/bin/cavelight-node and its shaders; unless --no-program)
  the cluster config, at the node's "config" path or ETC/NAME.json
  the config's scene when it is a file (.gltf with the buffers and images it names, or
  .glb), at the path the node opens: as written when absolute, else in the node's working
  folder ("workdir", or the unit's default /home/USER); a relative path is read from here
  the host's own keys (NODE.key, NODE.pub of its nodes, master.pub), never another
  host's private key, in the config's security.keys folder as seen from there
  /etc/systemd/system/cavelight-node@.service (scripts/systemd/) and one drop-in per node
  with its program ("exe"), working folder ("workdir"), config and X display ("display")
and enables and starts cavelight-node@NODE. Run it again after changing the config.

Options:
  --prefix DIR     where the node program goes on the hosts (default /opt/cavelight)
  --etc DIR        where the config goes when a node names none (default /etc/cavelight)
  --user USER      the account the nodes run as, the one owning the X session (default cavelight)
  --build DIR      the build folder to take cavelight-node from (default build)
  --no-program     the hosts have cavelight-node already (built there, or a package)
  --ssh CMD        the remote shell (default "ssh"); --scp CMD the copy (default "scp")
  --stage DIR      stage into DIR and keep it (default a temporary folder)
  --dry-run        stage and print the commands, run nothing
"""
import argparse
import json
import os
import struct
import urllib.parse
import shlex
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def fail(msg):
    print("install_nodes: " + msg, file=sys.stderr)
    sys.exit(1)


def keys_folder(config_path, cfg):
    """The config's key folder, relative to the config's own folder unless absolute."""
    sec = cfg.get("security", {})
    if sec.get("mode", "curve") == "insecure":
        return None
    stem = os.path.basename(config_path)
    stem = stem[:-5] if stem.endswith(".json") else stem
    return sec.get("keys", stem + ".keys")


def scene_files(path):
    """The scene file and the files it names (a .gltf's or .glb's buffers and images),
    relative to its folder; [] for a built-in scene's name."""
    if not path.lower().endswith((".gltf", ".glb")):
        return []
    try:
        data = open(path, "rb").read()
        if path.lower().endswith(".glb"):
            (length,) = struct.unpack_from("<I", data, 12)
            doc = json.loads(data[20:20 + length])
        else:
            doc = json.loads(data)
    except (OSError, ValueError, struct.error) as e:
        fail("scene %s: %s" % (path, e))
    names = [os.path.basename(path)]
    for item in doc.get("buffers", []) + doc.get("images", []):
        uri = item.get("uri", "") if isinstance(item, dict) else ""
        if uri and not uri.startswith("data:"):
            names.append(os.path.normpath(urllib.parse.unquote(uri)))
    for n in names:
        if n.startswith("..") or os.path.isabs(n):
            fail("scene %s names %s outside its folder: copy that file by hand" % (path, n))
        if not os.path.isfile(os.path.join(os.path.dirname(path), n)):
            fail("scene %s: %s is missing" % (path, os.path.join(os.path.dirname(path), n)))
    return names


def stage_program(build, d):
    """The render node as `cmake --install --component node` lays it out, under d/prefix."""
    r = subprocess.run(["cmake", "--install", build, "--prefix", os.path.join(d, "prefix"), "--component", "node"],
                       stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        fail("cmake --install %s --component node: %s" % (build, r.stderr.strip().splitlines()[-1:]))


def main():
    ap = argparse.ArgumentParser(add_help=False)
    ap.add_argument("config", nargs="?")
    ap.add_argument("--prefix", default="/opt/cavelight")
    ap.add_argument("--etc", default="/etc/cavelight")
    ap.add_argument("--user", default="cavelight")
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--no-program", action="store_true")
    ap.add_argument("--ssh", default="ssh")
    ap.add_argument("--scp", default="scp")
    ap.add_argument("--stage")
    ap.add_argument("--dry-run", action="store_true")
    ap.add_argument("-h", "--help", action="store_true")
    args, unknown = ap.parse_known_args()
    if args.help:
        print(__doc__.strip())
        return 0
    if unknown or not args.config:
        fail("give CONFIG%s (see --help)" % ("; unknown " + " ".join(unknown) if unknown else ""))
    try:
        cfg = json.load(open(args.config))
    except (OSError, ValueError) as e:
        fail("%s: %s" % (args.config, e))
    node_exe = os.path.join(args.build, "cavelight-node")
    if not args.no_program and not os.access(node_exe, os.X_OK):
        fail("%s is not built: build it, give --build, or --no-program" % node_exe)
    keys_rel = keys_folder(args.config, cfg)
    keys_local = None
    if keys_rel:
        keys_local = keys_rel if os.path.isabs(keys_rel) else \
            os.path.join(os.path.dirname(os.path.abspath(args.config)), keys_rel)
        if not os.path.isfile(os.path.join(keys_local, "master.pub")):
            fail("no keys in %s: run cavelight-master --config %s --keygen first" % (keys_local, args.config))

    scene = cfg.get("scene", "")
    scene_names = scene_files(scene) if scene else []
    default_workdir = "/home/" + args.user
    stage = args.stage or tempfile.mkdtemp(prefix="cavelight-install-")
    template = open(os.path.join(ROOT, "scripts", "systemd", "cavelight-node@.service")).read()
    default_config = os.path.join(args.etc, os.path.basename(args.config))
    hosts = {}
    for n in cfg.get("nodes", []):
        hosts.setdefault(n.get("host", "localhost"), []).append(n)
    commands = []
    for host, nodes in hosts.items():
        d = os.path.join(stage, host)
        os.makedirs(os.path.join(d, "dropins"), exist_ok=True)
        unit = template
        for key, value in (("USER", args.user), ("WORKDIR", default_workdir), ("DISPLAY", ":0"),
                           ("XAUTHORITY", "/home/%s/.Xauthority" % args.user), ("PREFIX", args.prefix),
                           ("CONFIG", default_config)):
            unit = unit.replace("@%s@" % key, value)
        open(os.path.join(d, "cavelight-node@.service"), "w").write(unit)
        shutil.copy(args.config, os.path.join(d, "cluster.json"))
        script = ["set -e"]
        if not args.no_program:
            stage_program(args.build, d)
            script += ["mkdir -p %s" % shlex.quote(args.prefix),
                       "cp -R prefix/. %s/" % shlex.quote(args.prefix)]
        if scene_names:
            for f in scene_names:
                staged = os.path.join(d, "scene", f)
                os.makedirs(os.path.dirname(staged), exist_ok=True)
                shutil.copy(os.path.join(os.path.dirname(scene), f), staged)
            dests = sorted({os.path.dirname(scene) if os.path.isabs(scene) else
                            os.path.normpath(os.path.join(n.get("workdir") or default_workdir, os.path.dirname(scene)))
                            for n in nodes})
            script += ["install -D -m 644 %s %s" % (shlex.quote("scene/" + f), shlex.quote(os.path.join(dest, f)))
                       for dest in dests for f in scene_names]
        configs = sorted({n.get("config") or default_config for n in nodes})
        for c in configs:
            script.append("install -D -m 644 cluster.json %s" % shlex.quote(c))
        if keys_rel:
            os.makedirs(os.path.join(d, "keys"), exist_ok=True)
            names = ["master.pub"] + [f for n in nodes for f in (n["name"] + ".key", n["name"] + ".pub")]
            for f in names:
                shutil.copy(os.path.join(keys_local, f), os.path.join(d, "keys", f))
            for c in configs:
                kdir = keys_rel if os.path.isabs(keys_rel) else os.path.join(os.path.dirname(c), keys_rel)
                script.append("mkdir -p %s" % shlex.quote(kdir))
                for f in names:
                    mode = "600" if f.endswith(".key") else "644"
                    script.append("install -m %s -o %s keys/%s %s" % (mode, shlex.quote(args.user), f,
                                                                   shlex.quote(os.path.join(kdir, f))))
        script.append("install -m 644 cavelight-node@.service /etc/systemd/system/")
        for n in nodes:
            name = n["name"]
            exe = n.get("exe") or args.prefix + "/bin/cavelight-node"
            conf = ["[Service]"]
            if n.get("workdir"):
                conf.append("WorkingDirectory=" + n["workdir"])
            conf.append("Environment=DISPLAY=" + n.get("display", ":0"))
            conf += ["ExecStart=", "ExecStart=%s --cluster %s --name %s" % (exe, n.get("config") or default_config,
                                                                            name)]
            open(os.path.join(d, "dropins", name + ".conf"), "w").write("\n".join(conf) + "\n")
            unit_dir = "/etc/systemd/system/cavelight-node@%s.service.d" % name
            script += ["mkdir -p " + unit_dir, "install -m 644 dropins/%s.conf %s/node.conf" % (name, unit_dir)]
        script.append("systemctl daemon-reload")
        for n in nodes:
            script.append("systemctl enable cavelight-node@%s" % n["name"])
            script.append("systemctl restart cavelight-node@%s" % n["name"])
        open(os.path.join(d, "install.sh"), "w").write("\n".join(script) + "\n")
        remote = "/tmp/cavelight-install"
        commands.append(shlex.split(args.ssh) + [host, "rm -rf %s && mkdir -p %s" % (remote, remote)])
        commands.append(shlex.split(args.scp) + ["-r"] + [os.path.join(d, f) for f in sorted(os.listdir(d))] +
                        ["%s:%s/" % (host, remote)])
        commands.append(shlex.split(args.ssh) + [host, "cd %s && sudo sh install.sh" % remote])
    for c in commands:
        print(" ".join(shlex.quote(x) for x in c))
        if not args.dry_run:
            r = subprocess.run(c)
            if r.returncode != 0:
                fail("%s failed (exit %d)" % (c[0], r.returncode))
    print("install_nodes: %s %d nodes on %d hosts%s" % ("staged" if args.dry_run else "installed",
                                                         sum(len(v) for v in hosts.values()), len(hosts),
                                                         " in " + stage if args.dry_run or args.stage else ""))
    if not args.stage and not args.dry_run:
        shutil.rmtree(stage)
    return 0


if __name__ == "__main__":
    sys.exit(main())

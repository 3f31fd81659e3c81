#!/usr/bin/env python3
"""Writes scenes/turntable.gltf: scenes/room.gltf's room with parts that move, for the
moving-objects tests and docs/app.md.

Nodes (each a scene object, docs/app.md): "room" (the room of make_room_gltf.py, static),
"turntable" (a low grey disk-like box at x = -0.8, z = -1.0 that turns about +y, one turn
in 8 s: rotation keys every 2 s, LINEAR, so its quaternions slerp), its child "statue" (a
tall white box standing on it 0.3 m off its axis: it goes round with the table), and "lift"
(a yellow box beside the right wall that STEPs between 0 and 0.6 m up every 2 s: a
translation channel with STEP keys). One file, the buffer embedded as a base64 data URI
(python3 scripts/make_turntable_gltf.py [OUT])."""
import base64
import json
import math
import os
import struct
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_room_gltf as room  # noqa: E402

MATERIALS = room.MATERIALS + [("grey", [0.4, 0.4, 0.4])]


def add_mesh(blob, views, accessors, parts):
    """parts: (material, vertices) pairs -> a mesh's primitives."""
    primitives = []
    for mat, verts in parts:
        pos = b"".join(struct.pack("<3f", *p) for p, _ in verts)
        nrm = b"".join(struct.pack("<3f", *n) for _, n in verts)
        for data, kind in ((pos, "POSITION"), (nrm, "NORMAL")):
            views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)})
            blob += data
            acc = {"bufferView": len(views) - 1, "componentType": 5126, "count": len(verts), "type": "VEC3"}
            if kind == "POSITION":
                acc["min"] = [min(p[a] for p, _ in verts) for a in range(3)]
                acc["max"] = [max(p[a] for p, _ in verts) for a in range(3)]
            accessors.append(acc)
        primitives.append({"attributes": {"POSITION": len(accessors) - 2, "NORMAL": len(accessors) - 1},
                           "material": mat})
    return {"primitives": primitives}


def add_floats(blob, views, accessors, values, kind):
    """A float accessor of SCALAR, VEC3 or VEC4 values."""
    flat = [x for v in values for x in (v if isinstance(v, (list, tuple)) else [v])]
    data = struct.pack("<%df" % len(flat), *flat)
    views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)})
    blob += data
    acc = {"bufferView": len(views) - 1, "componentType": 5126, "count": len(values), "type": kind}
    if kind == "SCALAR":
        acc["min"], acc["max"] = [min(values)], [max(values)]
    accessors.append(acc)
    return len(accessors) - 1


def main(path):
    blob, views, accessors = bytearray(), [], []
    meshes = [
        add_mesh(blob, views, accessors, list(enumerate(room.geometry()))),
        add_mesh(blob, views, accessors, [(4, room.box((-0.45, 0.0, -0.45), (0.45, 0.08, 0.45)))]),
        add_mesh(blob, views, accessors, [(0, room.box((-0.12, 0.0, -0.12), (0.12, 1.1, 0.12)))]),
        add_mesh(blob, views, accessors, [(3, room.box((-0.25, 0.0, -0.25), (0.25, 0.5, 0.25)))]),
    ]
    times = [0.0, 2.0, 4.0, 6.0, 8.0]
    turns = [[0.0, math.sin(a / 2), 0.0, math.cos(a / 2)] for a in (t / 8.0 * 2 * math.pi for t in times)]
    lift = [[1.3, 0.6 * (i % 2), -0.8] for i in range(len(times))]
    t_acc = add_floats(blob, views, accessors, times, "SCALAR")
    doc = {
        "asset": {"version": "2.0", "generator": "cavelight scripts/make_turntable_gltf.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"name": "ceiling lamp", "type": "point", "color": [1.0, 0.92, 0.8], "intensity": 8.0}]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2, 3, 5]}],
        "nodes": [
            {"name": "room", "mesh": 0},
            {"name": "lamp", "translation": [0.0, room.H - 0.4, -0.5],
             "extensions": {"KHR_lights_punctual": {"light": 0}}},
            {"name": "view", "camera": 0, "translation": [0.3, 1.6, 2.2]},
            {"name": "turntable", "mesh": 1, "translation": [-0.8, 0.0, -1.0], "children": [4]},
            {"name": "statue", "mesh": 2, "translation": [0.3, 0.08, 0.0]},
            {"name": "lift", "mesh": 3, "translation": lift[0]},
        ],
        "animations": [{"name": "show", "samplers": [
            {"input": t_acc, "output": add_floats(blob, views, accessors, turns, "VEC4"), "interpolation": "LINEAR"},
            {"input": t_acc, "output": add_floats(blob, views, accessors, lift, "VEC3"), "interpolation": "STEP"}],
            "channels": [{"sampler": 0, "target": {"node": 3, "path": "rotation"}},
                         {"sampler": 1, "target": {"node": 5, "path": "translation"}}]}],
        "cameras": [{"name": "view", "type": "perspective",
                     "perspective": {"yfov": 1.0, "aspectRatio": 4.0 / 3.0, "znear": 0.05, "zfar": 20.0}}],
        "meshes": meshes,
        "materials": [{"name": n, "pbrMetallicRoughness": {"baseColorFactor": c + [1.0], "metallicFactor": 0.0,
                                                           "roughnessFactor": 0.8}} for n, c in MATERIALS],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}],
    }
    with open(path, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    here = os.path.dirname(os.path.abspath(__file__))
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "scenes", "turntable.gltf"))

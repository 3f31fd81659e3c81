#!/usr/bin/env python3
"""Writes scenes/room.gltf: a small closed room of our own for the README and the tests,
so that a glTF example runs from any clone.

A 4 x 2.6 x 5 m room (x across, y up, z along; the floor at y = 0), its walls facing in:
white floor, ceiling and end walls, a red left and a blue right wall. A yellow table
(0.9 m cube-ish box) and a tall white cabinet stand on the floor. One KHR_lights_punctual
point light hangs 0.4 m under the ceiling, and one perspective camera stands near the
open end at eye height looking down the room. Its intensity, 8 cd, puts the walls' mean
first-bounce radiance near middle grey at exposure 1 (docs/node.md, exposure_from_light).
One file: the buffer is embedded as a base64 data URI. The format is glTF 2.0; this
script only writes it (python3 scripts/make_room_gltf.py [OUT])."""
import base64
import json
import os
import struct
import sys

W, H, D = 4.0, 2.6, 5.0
X0, X1, Z0, Z1 = -W / 2, W / 2, -D / 2, D / 2

MATERIALS = [
    ("white", [0.75, 0.75, 0.75]),
    ("red", [0.75, 0.10, 0.08]),
    ("blue", [0.10, 0.20, 0.70]),
    ("yellow", [0.80, 0.65, 0.15]),
]


def quad(a, b, c, d, n):
    """Two triangles a b c, a c d, counter-clockwise seen from the side n points to."""
    return [(a, n), (b, n), (c, n), (a, n), (c, n), (d, n)]


def box(lo, hi):
    """An axis-aligned box, faces out."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    return (quad((x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1), (0, 0, 1)) +
            quad((x1, y0, z0), (x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (0, 0, -1)) +
            quad((x1, y0, z1), (x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (1, 0, 0)) +
            quad((x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0), (-1, 0, 0)) +
            quad((x0, y1, z1), (x1, y1, z1), (x1, y1, z0), (x0, y1, z0), (0, 1, 0)))


def geometry():
    """Triangles per material index."""
    white = (quad((X0, 0, Z0), (X0, 0, Z1), (X1, 0, Z1), (X1, 0, Z0), (0, 1, 0)) +    # floor
             quad((X0, H, Z0), (X1, H, Z0), (X1, H, Z1), (X0, H, Z1), (0, -1, 0)) +   # ceiling
             quad((X0, 0, Z0), (X1, 0, Z0), (X1, H, Z0), (X0, H, Z0), (0, 0, 1)) +    # far wall
             quad((X1, 0, Z1), (X0, 0, Z1), (X0, H, Z1), (X1, H, Z1), (0, 0, -1)) +   # near wall
             box((0.6, 0.0, -2.3), (1.6, 2.0, -1.7)))                                 # cabinet
    red = quad((X0, 0, Z1), (X0, 0, Z0), (X0, H, Z0), (X0, H, Z1), (1, 0, 0))
    blue = quad((X1, 0, Z0), (X1, 0, Z1), (X1, H, Z1), (X1, H, Z0), (-1, 0, 0))
    yellow = box((-1.2, 0.0, -1.0), (-0.3, 0.75, -0.2))
    return [white, red, blue, yellow]


def main(path):
    blob = bytearray()
    views, accessors, primitives = [], [], []
    for mat, verts in enumerate(geometry()):
        pos = b"".join(struct.pack("<3f", *p) for p, _ in verts)
        nrm = b"".join(struct.pack("<3f", *n) for _, n in verts)
        for data, kind in ((pos, "POSITION"), (nrm, "NORMAL")):
            views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": 34962})
            blob += data
            acc = {"bufferView": len(views) - 1, "componentType": 5126, "count": len(verts), "type": "VEC3"}
            if kind == "POSITION":
                acc["min"] = [min(p[a] for p, _ in verts) for a in range(3)]
                acc["max"] = [max(p[a] for p, _ in verts) for a in range(3)]
            accessors.append(acc)
        primitives.append({"attributes": {"POSITION": len(accessors) - 2, "NORMAL": len(accessors) - 1},
                           "material": mat})
    doc = {
        "asset": {"version": "2.0", "generator": "cavelight scripts/make_room_gltf.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"name": "ceiling lamp", "type": "point", "color": [1.0, 0.92, 0.8], "intensity": 8.0}]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [
            {"name": "room", "mesh": 0},
            {"name": "lamp", "translation": [0.0, H - 0.4, -0.5], "extensions": {"KHR_lights_punctual": {"light": 0}}},
            {"name": "view", "camera": 0, "translation": [0.3, 1.6, 2.2]},
        ],
        "cameras": [{"name": "view", "type": "perspective",
                     "perspective": {"yfov": 1.0, "aspectRatio": 4.0 / 3.0, "znear": 0.05, "zfar": 20.0}}],
        "meshes": [{"name": "room", "primitives": primitives}],
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
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "scenes", "room.gltf"))

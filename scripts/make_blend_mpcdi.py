#!/usr/bin/env python3
"""Writes configs/clusters/powerwall-blend.mpcdi: the MPCDI file (VESA MPCDI 2.0, profile 2d)
of configs/clusters/powerwall-blend-local.json's two overlapping projectors.

Each projector is its own buffer with one region covering it ("left", "right"), 160 x 150
pixels. Their screens (wall-l, wall-r in the config) are 1.6 x 1.5 m of one wall and
overlap by 0.2 m: 20 pixel columns, the right 20 of "left" and the left 20 of "right".
The projectors are taken as perfectly aligned to their screens, so each warp is the
identity: a 2 x 2 grid in MPCDI's fill layout, whose samples sit at the cell centres
(u, v = 0.25 and 0.75). The alpha maps ramp across the overlap with a smoothstep in
linear light, so that the two projectors' light adds up to one projector's:
alpha_left + alpha_right = 1 at every overlap column. They are stored 8-bit grey with
gammaEmbedded 2.2 (value = round(255 alpha^(1/2.2))), the common case in real files.

Deterministic (fixed zip dates, sorted members), so the test that regenerates it can
compare the members with the committed file. Usage: make_blend_mpcdi.py [OUT]."""
import os
import struct
import sys
import zipfile
import zlib

WIDTH, HEIGHT, OVERLAP = 160, 150, 20
GAMMA = 2.2
DATE = (2024, 1, 1, 0, 0, 0)


def smoothstep(t):
    return t * t * (3 - 2 * t)


def alpha(region, col):
    """Linear-light blend weight of a projector column."""
    if region == "left":
        k = col - (WIDTH - OVERLAP)
        return 1.0 if k < 0 else 1.0 - smoothstep((k + 0.5) / OVERLAP)
    return smoothstep((col + 0.5) / OVERLAP) if col < OVERLAP else 1.0


def png_grey8(width, height, rows):
    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + bytes(r) for r in rows)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def alpha_png(region):
    row = [round(255 * alpha(region, c) ** (1 / GAMMA)) for c in range(WIDTH)]
    return png_grey8(WIDTH, HEIGHT, [row] * HEIGHT)


def identity_pfm():
    """2 x 2 samples, rows bottom first, little-endian: u, v at the cell centres, no error."""
    nan = float("nan")
    samples = [(0.25, 0.25), (0.75, 0.25), (0.25, 0.75), (0.75, 0.75)]
    data = b"".join(struct.pack("<3f", u, v, nan) for u, v in samples)
    return b"PF\n2 2\n-1.0\n" + data


def xml():
    buffers, filesets = [], []
    for region in ("left", "right"):
        buffers.append(
            f'    <buffer id="projector-{region}" xResolution="{WIDTH}" yResolution="{HEIGHT}">\n'
            f'      <region id="{region}" x="0" y="0" xSize="1" ySize="1" '
            f'xResolution="{WIDTH}" yResolution="{HEIGHT}">\n'
            f'        <color><decode type="gamma" gamma="{GAMMA}"/><encode type="gamma" gamma="{GAMMA}"/></color>\n'
            f'      </region>\n'
            f'    </buffer>\n')
        filesets.append(
            f'    <fileset region="{region}">\n'
            f'      <geometryWarpFile><path>{region}_warp.pfm</path><interpolation>linear</interpolation>'
            f'</geometryWarpFile>\n'
            f'      <alphaMap><path>{region}_alpha.png</path><componentDepth>1</componentDepth>'
            f'<bitDepth>8</bitDepth><gammaEmbedded>{GAMMA}</gammaEmbedded></alphaMap>\n'
            f'    </fileset>\n')
    return ('<?xml version="1.0" encoding="utf-8"?>\n'
            '<MPCDI profile="2d" geometry="1" color="1" date="2024-01-01 00:00:00" version="2.0">\n'
            '  <display>\n' + "".join(buffers) + '  </display>\n'
            '  <files>\n' + "".join(filesets) + '  </files>\n'
            '</MPCDI>\n').encode()


def members():
    out = {"mpcdi.xml": xml()}
    for region in ("left", "right"):
        out[f"{region}_warp.pfm"] = identity_pfm()
        out[f"{region}_alpha.png"] = alpha_png(region)
    return out


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "configs", "clusters",
                                                              "powerwall-blend.mpcdi")
    with zipfile.ZipFile(path, "w") as z:
        for name, data in sorted(members().items()):
            info = zipfile.ZipInfo(name, DATE)
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o644 << 16
            z.writestr(info, data)


if __name__ == "__main__":
    main()

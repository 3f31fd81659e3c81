"""Reads an 8-bit RGB PNG into rows of bytes with the standard library only (zlib and every
PNG filter), for the integration tests that check pixels. Not a general PNG reader."""
import struct
import zlib


def read_png(path):
    """(width, height, rows): rows[y][3 * x + c], the top row first."""
    d = open(path, "rb").read()
    assert d[:8] == b"\x89PNG\r\n\x1a\n", path
    i, data = 8, b""
    while i < len(d):
        n, kind = struct.unpack(">I4s", d[i:i + 8])
        if kind == b"IHDR":
            w, h, depth, colour = struct.unpack(">IIBB", d[i + 8:i + 18])
            assert depth == 8 and colour == 2, (path, depth, colour)
        elif kind == b"IDAT":
            data += d[i + 8:i + 8 + n]
        i += 12 + n
    raw, stride, prev, rows = zlib.decompress(data), w * 3, bytearray(w * 3), []
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            a, b, c = line[x - 3] if x >= 3 else 0, prev[x], prev[x - 3] if x >= 3 else 0
            p = a + b - c
            paeth = a if abs(p - a) <= abs(p - b) and abs(p - a) <= abs(p - c) else b if abs(p - b) <= abs(p - c) else c
            line[x] = (line[x] + (0, a, b, (a + b) // 2, paeth)[f]) & 255
        rows.append(line)
        prev = line
    return w, h, rows

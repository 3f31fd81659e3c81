#!/usr/bin/env python3
"""The tracker-to-CAVE transform from measured point pairs (docs/calibration.md).

Usage: scripts/fit_tracker.py POINTS
POINTS has one pair a line: the tracker position the master printed (--print-poses,
"tracker" columns, with tracker_to_cave left out of the config) and where that point is
in CAVE coordinates, six numbers: tx ty tz  cx cy cz ('#' starts a comment). Three pairs
not on one line are the least; more average out the measuring error.

Prints the "tracker_to_cave" object for the cluster config (translation, rotation_deg as
the config applies it: Rz * Ry * Rx, scale) and each pair's residual in millimetres.
The fit is least squares over rotation, uniform scale and translation: Horn's closed form
(the rotation is the eigenvector of the largest eigenvalue of a 4x4 matrix built from
the pairs' cross-covariance), pure Python.
"""
import json
import math
import sys


def jacobi_eigen(a):
    """Eigenvalues and eigenvectors (columns) of a small symmetric matrix."""
    n = len(a)
    a = [row[:] for row in a]
    v = [[float(i == j) for j in range(n)] for i in range(n)]
    for _ in range(100):
        off = sum(a[i][j] ** 2 for i in range(n) for j in range(n) if i != j)
        if off < 1e-30:
            break
        for p in range(n):
            for q in range(p + 1, n):
                if abs(a[p][q]) < 1e-300:
                    continue
                theta = (a[q][q] - a[p][p]) / (2 * a[p][q])
                t = math.copysign(1.0, theta) / (abs(theta) + math.sqrt(theta * theta + 1))
                c = 1 / math.sqrt(t * t + 1)
                s = t * c
                for k in range(n):
                    akp, akq = a[k][p], a[k][q]
                    a[k][p], a[k][q] = c * akp - s * akq, s * akp + c * akq
                for k in range(n):
                    apk, aqk = a[p][k], a[q][k]
                    a[p][k], a[q][k] = c * apk - s * aqk, s * apk + c * aqk
                for k in range(n):
                    vkp, vkq = v[k][p], v[k][q]
                    v[k][p], v[k][q] = c * vkp - s * vkq, s * vkp + c * vkq
    return [a[i][i] for i in range(n)], v


def fit(tracker, cave):
    n = len(tracker)
    ta = [sum(p[i] for p in tracker) / n for i in range(3)]
    ca = [sum(p[i] for p in cave) / n for i in range(3)]
    a = [[p[i] - ta[i] for i in range(3)] for p in tracker]
    b = [[p[i] - ca[i] for i in range(3)] for p in cave]
    s = [[sum(a[k][i] * b[k][j] for k in range(n)) for j in range(3)] for i in range(3)]
    (sxx, sxy, sxz), (syx, syy, syz), (szx, szy, szz) = s
    horn = [[sxx + syy + szz, syz - szy, szx - sxz, sxy - syx],
            [syz - szy, sxx - syy - szz, sxy + syx, szx + sxz],
            [szx - sxz, sxy + syx, -sxx + syy - szz, syz + szy],
            [sxy - syx, szx + sxz, syz + szy, -sxx - syy + szz]]
    values, vectors = jacobi_eigen(horn)
    best = max(range(4), key=lambda i: values[i])
    w, x, y, z = (vectors[k][best] for k in range(4))
    r = [[w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)],
         [2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)],
         [2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z]]
    ra = [[sum(r[i][j] * p[j] for j in range(3)) for i in range(3)] for p in a]
    scale = sum(ra[k][i] * b[k][i] for k in range(n) for i in range(3)) / \
        sum(a[k][i] ** 2 for k in range(n) for i in range(3))
    t = [ca[i] - scale * sum(r[i][j] * ta[j] for j in range(3)) for i in range(3)]
    return r, scale, t


def main():
    if len(sys.argv) != 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(sys.argv) == 2 else 2
    tracker, cave = [], []
    for number, line in enumerate(open(sys.argv[1]), 1):
        line = line.split("#")[0].split()
        if not line:
            continue
        if len(line) != 6:
            print("fit_tracker: %s:%d: give six numbers: tx ty tz cx cy cz" % (sys.argv[1], number),
                  file=sys.stderr)
            return 2
        v = [float(x) for x in line]
        tracker.append(v[:3])
        cave.append(v[3:])
    if len(tracker) < 3:
        print("fit_tracker: %s: give at least three pairs" % sys.argv[1], file=sys.stderr)
        return 2
    r, scale, t = fit(tracker, cave)
    # R = Rz(c) Ry(b) Rx(a), as cluster_config.c composes rotation_deg.
    b = math.asin(max(-1.0, min(1.0, -r[2][0])))
    a = math.atan2(r[2][1], r[2][2])
    c = math.atan2(r[1][0], r[0][0])
    out = {"translation": [round(v, 5) for v in t],
           "rotation_deg": [round(math.degrees(v), 4) for v in (a, b, c)],
           "scale": round(scale, 7)}
    print('"tracker_to_cave": ' + json.dumps(out))
    for p, q in zip(tracker, cave):
        m = [scale * sum(r[i][j] * p[j] for j in range(3)) + t[i] for i in range(3)]
        err = math.sqrt(sum((m[i] - q[i]) ** 2 for i in range(3)))
        print("# %8.4f %8.4f %8.4f -> %8.4f %8.4f %8.4f  residual %.1f mm" % (*p, *m, err * 1000))
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""The Middlebury temple ring's ground truth, corrected, and its photos in
ring order.

Photos templeR0032-0047 are upside down on disk against the frames that
templeR_par.txt describes (the copy in ../shared/data rotated them the wrong
way; Middlebury's README: "some images may appear upside-down"): their
cameras are rolled 180 degrees about the optical axis. Every reconstruction
placed them correctly and tmr_eval reported ~180 degrees for each. The
corrected ground truth rolls those cameras back (R' = Rz(180) R,
t' = Rz(180) t) and gives them a camera with the principal point mirrored.

Usage: templering_gt.py GT_TEXT_DIR OUT_DIR
Writes OUT_DIR/{cameras,images,points3D}.txt and prints the image names
sorted by azimuth around the ring's axis (through the centroid of the
centres, normal to their best-fit plane), one per line, starting at the
photo closest to azimuth 0.
"""
import math
import os
import sys

FLIPPED = {f"templeR{i:04d}.png" for i in range(32, 48)}


def quat_to_matrix(w, x, y, z):
    return [
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ]


def centre(q, t):
    r = quat_to_matrix(*q)
    return [-sum(r[j][i] * t[j] for j in range(3)) for i in range(3)]


def main(gt, out):
    os.makedirs(out, exist_ok=True)
    cams = [l for l in open(os.path.join(gt, "cameras.txt")) if l.strip() and not l.startswith("#")]
    assert len(cams) == 1, "expected one camera"
    cid, model, w, h, fx, fy, cx, cy = cams[0].split()
    with open(os.path.join(out, "cameras.txt"), "w") as f:
        f.write(f"{cid} {model} {w} {h} {fx} {fy} {cx} {cy}\n")
        f.write(f"2 {model} {w} {h} {fx} {fy} {float(w) - float(cx)} {float(h) - float(cy)}\n")
    lines = [l.rstrip("\n") for l in open(os.path.join(gt, "images.txt")) if not l.startswith("#")]
    centres = {}
    with open(os.path.join(out, "images.txt"), "w") as f:
        for line in lines:
            parts = line.split()
            if len(parts) != 10:
                continue
            iid, qw, qx, qy, qz, tx, ty, tz, _, name = parts
            q = [float(v) for v in (qw, qx, qy, qz)]
            t = [float(v) for v in (tx, ty, tz)]
            centres[name] = centre(q, t)
            camera = cid
            if name in FLIPPED:  # Rz(180) = quaternion (0, 0, 0, 1) on the left
                w_, x_, y_, z_ = q
                q = [-z_, -y_, x_, w_]
                t = [-t[0], -t[1], t[2]]
                camera = "2"
            f.write(f"{iid} {' '.join(repr(v) for v in q)} {' '.join(repr(v) for v in t)} {camera} {name}\n\n")
    open(os.path.join(out, "points3D.txt"), "w").close()
    # Ring order: azimuth in the best-fit plane of the centres.
    names = sorted(centres)
    c0 = [sum(centres[n][i] for n in names) / len(names) for i in range(3)]
    d = {n: [centres[n][i] - c0[i] for i in range(3)] for n in names}
    cov = [[sum(d[n][i] * d[n][j] for n in names) for j in range(3)] for i in range(3)]
    # Plane normal: smallest-eigenvalue eigenvector (power iteration on the
    # inverse-free shifted matrix trace*I - cov).
    tr = sum(cov[i][i] for i in range(3))
    m = [[(tr if i == j else 0) - cov[i][j] for j in range(3)] for i in range(3)]
    v = [1.0, 1.0, 1.0]
    for _ in range(200):
        v = [sum(m[i][j] * v[j] for j in range(3)) for i in range(3)]
        s = math.sqrt(sum(x * x for x in v))
        v = [x / s for x in v]
    e1 = d[names[0]]
    dot = sum(e1[i] * v[i] for i in range(3))
    e1 = [e1[i] - dot * v[i] for i in range(3)]
    s = math.sqrt(sum(x * x for x in e1))
    e1 = [x / s for x in e1]
    e2 = [v[1] * e1[2] - v[2] * e1[1], v[2] * e1[0] - v[0] * e1[2], v[0] * e1[1] - v[1] * e1[0]]
    azimuth = {n: math.degrees(math.atan2(sum(d[n][i] * e2[i] for i in range(3)),
                                          sum(d[n][i] * e1[i] for i in range(3)))) % 360
               for n in names}
    for n in sorted(names, key=lambda n: azimuth[n]):
        print(f"{n} {azimuth[n]:.1f}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])

#!/usr/bin/env python3
"""Grind points of one scored run against the surface the exact map gives.

docs/reconstruction.md, "Grind planes in physical terms". Usage, after
`REAL=1 toolchain/eval-scenes.sh PETRA WORK` and
`DISPARITY=truth REAL=1 toolchain/eval-scenes.sh PETRA WORK`:

    python3 tests/bench/grind_point_check.py WORK/real-eval WORK/real-eval-truth

Per plane of each scene's planes.json in the first folder: the exact-map run's cloud.ply points
within the grinder's radius (10 mm) of the grind point across its normal, and within 20 mm along
it; the median of their offsets along the normal is the grind point's distance from the surface.
Prints the median, 90th percentile and maximum over the planes.
"""
import json, os, statistics, struct, sys

RADIUS_MM, DEPTH_MM, MIN_POINTS = 10.0, 20.0, 20


def cloud_points(path):
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode()
    count = int(next(l for l in header.split("\n") if l.startswith("element vertex")).split()[2])
    step = 16  # x, y, z float32; red, green, blue, gray uint8 (sim/eval PLY)
    return [struct.unpack_from("<3f", data, end + i * step) for i in range(count)]


def offset_under(points, g, n):
    along = []
    for p in points:
        q = (p[0] - g[0], p[1] - g[1], p[2] - g[2])
        a = q[0] * n[0] + q[1] * n[1] + q[2] * n[2]
        if abs(a) >= DEPTH_MM:
            continue
        across2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] - a * a
        if across2 <= RADIUS_MM * RADIUS_MM:
            along.append(a)
    return abs(statistics.median(along)) if len(along) >= MIN_POINTS else None


def main(run, exact):
    found = []
    for scene in sorted(os.listdir(run)):
        planes_path, cloud_path = f"{run}/{scene}/planes.json", f"{exact}/{scene}/cloud.ply"
        if not (os.path.exists(planes_path) and os.path.exists(cloud_path)):
            continue
        points = cloud_points(cloud_path)
        for plane in json.load(open(planes_path))["planes"]:
            d = offset_under(points, plane["grind_point_mm"], plane["normal"])
            if d is not None:
                found.append(d)
    found.sort()
    print(f"{len(found)} planes: grind point to the exact map's surface under its disc: "
          f"median {statistics.median(found):.2f}, 90 % {found[int(0.9 * len(found))]:.2f}, "
          f"max {found[-1]:.2f} mm")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])

#!/usr/bin/env python3
"""Reported plane sigmas against the errors measured on a scored scene set.

docs/reconstruction.md, "Grind planes in physical terms". Usage, after
`toolchain/eval-scenes.sh PETRA WORK` has rendered and evaluated the clean set:

    python3 tests/bench/plane_sigma_check.py PETRA WORK

Per matched facet (each scene's planes.json and `petra score`): the normal error over the
reported normal 1-sigma and the centroid-plane distance over the offset 1-sigma. Prints the
normal ratio's median, 90th percentile and maximum, then the offset ratio's median and maximum.
"""
import json, os, re, subprocess, sys, statistics
petra, work = sys.argv[1], sys.argv[2]
rn, ro = [], []
for s in sorted(d for d in os.listdir(f"{work}/set") if d.startswith("scene_")):
    pj = f"{work}/eval/{s}/planes.json"
    planes = json.load(open(pj))["planes"]
    out = subprocess.run([petra, "score", "--truth", f"{work}/set/{s}/truth.json", "--planes", pj],
                         capture_output=True, text=True).stdout
    for m in re.finditer(r"^(\d+)\s+[0-9.]+\s+(\d+)\s+([0-9.]+)\s+([0-9.]+)\s+(yes|no)", out, re.M):
        p = planes[int(m.group(2))]
        rn.append(float(m.group(3)) / p["normal_sigma_deg"])
        ro.append(float(m.group(4)) / p["offset_sigma_mm"])
print(statistics.median(rn), sorted(rn)[int(.9 * len(rn))], max(rn), statistics.median(ro), max(ro))

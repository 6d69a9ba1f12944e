#!/usr/bin/env bash
# Renders the simulator's standard scene set (or reuses it), runs `petra eval`
# on every scene with the truth's ROI and plane count, scores each with
# `petra score`, and prints one table row per scene plus the summary used in
# docs/performance.md.
#   toolchain/eval-scenes.sh [PETRA_BINARY] [WORK_DIR] [extra petra eval options...]
# e.g. toolchain/eval-scenes.sh build/release/sim/petra out/eval-scenes --method gc
# With DISPARITY=truth in the environment each scene replays its
# disparity_truth.pfm instead of matching (the reconstruction alone).
set -euo pipefail
PETRA=${1:-build/release/sim/petra}
WORK=${2:-out/eval-scenes}
shift $(( $# > 2 ? 2 : $# )) || true
mkdir -p "$WORK"
if [ ! -f "$WORK/set/scene_23/truth.json" ]; then
  "$PETRA" sim set --out "$WORK/set" > "$WORK/set.log"
fi
python3 - "$PETRA" "$WORK" "$@" <<'PY'
import json, math, os, re, subprocess, sys, statistics
petra, work, extra = sys.argv[1], sys.argv[2], sys.argv[3:]
rows, normal_errs, dists, count_ok, on_facet_all, matched_all = [], [], [], 0, 0, 0
# One output folder per configuration, so runs of both matchers share the set.
label = "eval" + "".join("-" + a.lstrip("-") for a in extra) + \
        ("-truth" if os.environ.get("DISPARITY") == "truth" else "")
scenes = sorted(d for d in os.listdir(os.path.join(work, "set")) if d.startswith("scene_"))
for s in scenes:
    sd = os.path.join(work, "set", s)
    truth = json.load(open(os.path.join(sd, "truth.json")))
    roi = ",".join(str(v) for v in truth["roi"])
    out = os.path.join(work, label, s)
    cmd = [petra, "eval", "--calib", f"{sd}/calib.json", "--left", f"{sd}/left.png", "--right", f"{sd}/right.png",
           "--roi", roi, "--planes", str(truth["planes"]), "--out", out] + extra
    if os.environ.get("DISPARITY") == "truth":
        cmd += ["--disparity", f"{sd}/disparity_truth.pfm"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    sc = truth["scene"]
    desc = f"{sc['boundary']:5s} {sc['shape']:7s} sun {sc['sun_elevation_deg']:4.0f}"
    if r.returncode != 0:
        rows.append(f"| {s} | {desc} | {truth['planes']} | - | failed: {r.stderr.strip()[:90]} |")
        continue
    cpu = re.search(r"total ([0-9.]+) CPU ms", r.stdout)
    sr = subprocess.run([petra, "score", "--truth", f"{sd}/truth.json", "--planes", f"{out}/planes.json"],
                        capture_output=True, text=True)
    found = len(json.load(open(f"{out}/planes.json"))["planes"])
    count_ok += found == truth["planes"]
    errs = []
    for line in sr.stdout.splitlines():
        m = re.match(r"^(\d+)\s+([0-9.]+)\s+(\d+|-)\s+([0-9.]+|-)\s+([0-9.]+|-)\s+(yes|no|-)", line)
        if not m or m.group(3) == "-":
            continue
        ne, cd, on = float(m.group(4)), float(m.group(5)), m.group(6) == "yes"
        normal_errs.append(ne); dists.append(cd); matched_all += 1; on_facet_all += on
        errs.append(f"{ne:.2f}/{cd:.2f}{'' if on else '!'}")
    rows.append(f"| {s} | {desc} | {truth['planes']} | {found} | {' '.join(errs)} | {cpu.group(1) if cpu else '?'} |")
print("| scene | case | c | found | normal err deg / centroid-plane mm per facet (! = off facet) | CPU ms |")
print("|---|---|---|---|---|---|")
print("\n".join(rows))
if normal_errs:
    print(f"\nplane count right: {count_ok} of {len(scenes)}; matched facets {matched_all}; "
          f"normal error median {statistics.median(normal_errs):.2f} deg, max {max(normal_errs):.2f} deg; "
          f"centroid-plane distance median {statistics.median(dists):.2f} mm, max {max(dists):.2f} mm; "
          f"centroids on their facet {on_facet_all} of {matched_all}")
    # The issue's targets (19 of 20 scenes: the same 95 % share of this set).
    need = math.ceil(0.95 * len(scenes))
    def verdict(ok): return "met" if ok else "NOT met"
    print(f"targets: plane count >= {need} of {len(scenes)}: {verdict(count_ok >= need)}; "
          f"normal median <= 0.5 deg: {verdict(statistics.median(normal_errs) <= 0.5)}; "
          f"normal max <= 1.5 deg: {verdict(max(normal_errs) <= 1.5)}; "
          f"centroid-plane <= 1 mm: {verdict(max(dists) <= 1.0)}; "
          f"on the facet: {verdict(on_facet_all == matched_all)}")
PY

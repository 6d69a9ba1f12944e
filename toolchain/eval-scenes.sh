#!/usr/bin/env bash
# Renders the simulator's standard scene set (or reuses it), runs `petra eval`
# on every scene with the truth's ROI and plane count, scores each with
# `petra score`, and prints one table row per scene (docs/reconstruction.md)
# plus the summary used in docs/performance.md.
#   toolchain/eval-scenes.sh [PETRA_BINARY] [WORK_DIR] [extra petra eval options...]
# e.g. toolchain/eval-scenes.sh build/release/sim/petra out/eval-scenes --method gc
# With DISPARITY=truth in the environment each scene replays its
# disparity_truth.pfm instead of matching (the reconstruction alone).
# With REAL=1 it runs the realistic set (`petra sim set --real`, rendered into
# WORK/real-set) and checks the realistic set's targets (docs/scene.md); its
# summary is printed for the first 24 scenes (the table before the hard
# cases), for the rest (touching neighbours, the rock filling the ROI) and
# for all. Each scene's truth.json click is passed as --click (CLICK=0: not).
# With DRIFT_DEG=a the rig has drifted since its calibration: each scene's
# right camera is pitched by a deg about its own x axis in the calib.json
# petra eval gets (the images are unchanged), e.g. 0.1 deg: rows about 1.5-1.9
# px apart (docs/reconstruction.md "Calibration check").
set -euo pipefail
PETRA=${1:-build/release/sim/petra}
WORK=${2:-out/eval-scenes}
shift $(( $# > 2 ? 2 : $# )) || true
mkdir -p "$WORK"
SET=set
SET_OPTS=()
if [ "${REAL:-0}" = 1 ]; then SET=real-set; SET_OPTS=(--real); fi
if [ ! -f "$WORK/$SET/done" ]; then
  # Scenes without the marker are someone else's: never render over them.
  if compgen -G "$WORK/$SET/scene_*" > /dev/null; then
    echo "eval-scenes: $WORK/$SET holds scenes but no 'done' file; refusing to render over them" \
         "(touch $WORK/$SET/done to use them)" >&2
    exit 2
  fi
  "$PETRA" sim set "${SET_OPTS[@]}" --out "$WORK/$SET" > "$WORK/$SET.log"
  touch "$WORK/$SET/done"
fi
python3 - "$PETRA" "$WORK" "$SET" "$@" <<'PY'
import json, math, os, re, subprocess, sys, statistics
petra, work, set_dir, extra = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
real = set_dir == "real-set"
rows = []
# One output folder per configuration, so runs of both matchers share the set.
use_click = os.environ.get("CLICK", "1") != "0"
drift = os.environ.get("DRIFT_DEG")
label = ("real-" if real else "") + "eval" + "".join("-" + a.lstrip("-") for a in extra) + \
        ("-truth" if os.environ.get("DISPARITY") == "truth" else "") + ("" if use_click else "-noclick") + \
        (f"-drift{drift}" if drift else "")

def drifted_calib(src, deg, dst):
    """src's calib.json with the right camera pitched by deg about its own x axis (centre kept)."""
    c = json.load(open(src))
    a = math.radians(float(deg))
    rx = [[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]]
    r = c["right"]
    R = [r["R"][0:3], r["R"][3:6], r["R"][6:9]]
    r["R"] = [sum(rx[i][k] * R[k][j] for k in range(3)) for i in range(3) for j in range(3)]
    r["T"] = [sum(rx[i][k] * r["T"][k] for k in range(3)) for i in range(3)]
    os.makedirs(os.path.dirname(dst), exist_ok=True)
    json.dump(c, open(dst, "w"))
    return dst
stats = []  # per scene: found == c, [(normal err, centroid dist, on facet)], refusal
scenes = sorted(d for d in os.listdir(os.path.join(work, set_dir)) if d.startswith("scene_")
          and os.path.isdir(os.path.join(work, set_dir, d)))
for s in scenes:
    sd = os.path.join(work, set_dir, s)
    truth = json.load(open(os.path.join(sd, "truth.json")))
    roi = ",".join(str(v) for v in truth["roi"])
    out = os.path.join(work, label, s)
    calib = f"{sd}/calib.json"
    if drift:
        calib = drifted_calib(calib, drift, os.path.join(work, label + "-calib", s + ".json"))
    cmd = [petra, "eval", "--calib", calib, "--left", f"{sd}/left.png", "--right", f"{sd}/right.png",
           "--roi", roi, "--planes", str(truth["planes"]), "--out", out] + extra
    if os.environ.get("DISPARITY") == "truth":
        cmd += ["--disparity", f"{sd}/disparity_truth.pfm"]
    if use_click and "click" in truth:
        cmd += ["--click", ",".join(str(v) for v in truth["click"])]
    r = subprocess.run(cmd, capture_output=True, text=True)
    sc = truth["scene"]
    desc = f"{sc['boundary']:5s} {sc['shape']:7s} sun {sc['sun_elevation_deg']:4.0f}"
    if r.returncode != 0:
        reason = re.sub(r"[0-9.]+", "N", r.stderr.strip().splitlines()[-1] if r.stderr.strip() else "?")
        stats.append((False, [], reason))
        rows.append(f"| {s} | {desc} | {truth['planes']} | - | failed: {r.stderr.strip()[:90]} |")
        continue
    cpu = re.search(r"total ([0-9.]+) CPU ms", r.stdout)
    sr = subprocess.run([petra, "score", "--truth", f"{sd}/truth.json", "--planes", f"{out}/planes.json"],
                        capture_output=True, text=True)
    found = len(json.load(open(f"{out}/planes.json"))["planes"])
    seg = json.load(open(f"{out}/planes.json")).get("segmentation", "?")
    # Every plane is scored on the facet it lies on: a designed grind face, or
    # (after the "other visible facets" line) another real face, shown "fK:".
    errs, facets, other = [], [], False
    for line in sr.stdout.splitlines():
        other = other or line.startswith("planes on other visible facets")
        m = re.match(r"^(\d+)\s+([0-9.]+)\s+(\d+|-)\s+([0-9.]+|-)\s+([0-9.]+|-)\s+(yes|no|-)", line)
        if not m or m.group(3) == "-":
            continue
        ne, cd, on = float(m.group(4)), float(m.group(5)), m.group(6) == "yes"
        facets.append((ne, cd, on, other))
        errs.append(f"{'f' + m.group(1) + ':' if other else ''}{ne:.2f}/{cd:.2f}{'' if on else '!'}")
    stats.append((found == truth["planes"], facets, None))
    rows.append(f"| {s} | {desc} | {truth['planes']} | {found} | {' '.join(errs)} | {seg} | {cpu.group(1) if cpu else '?'} |")
print("| scene | case | c | found | normal err deg / centroid-plane mm per plane on its facet (! = off facet, fK: on undesigned facet K) | segmentation | CPU ms |")
print("|---|---|---|---|---|---|---|")
print("\n".join(rows))

def summary(title, part):
    count_ok = sum(1 for ok, _, _ in part if ok)
    facets = [f for _, fs, _ in part for f in fs]
    normal_errs, dists = [f[0] for f in facets], [f[1] for f in facets]
    matched_all, on_facet_all = len(facets), sum(1 for f in facets if f[2])
    undesigned = sum(1 for f in facets if f[3])
    refusals = {}
    for _, _, why in part:
        if why:
            refusals[why] = refusals.get(why, 0) + 1
    print(f"\n{title}:")
    if normal_errs:
        print(f"plane count right: {count_ok} of {len(part)}; matched facets {matched_all}; "
              f"normal error median {statistics.median(normal_errs):.2f} deg, max {max(normal_errs):.2f} deg; "
              f"centroid-plane distance median {statistics.median(dists):.2f} mm, max {max(dists):.2f} mm; "
              f"centroids on their facet {on_facet_all} of {matched_all}; planes on a face the truth did not design {undesigned}")
        # The issue's targets: clean set (issue 1: 95 % of scenes, 0.5 / 1.5 deg,
        # 1 mm); realistic set (issue 21: 90 %, 1.0 / 3.0 deg, 2 mm).
        share, med, mx, cd = (0.90, 1.0, 3.0, 2.0) if real else (0.95, 0.5, 1.5, 1.0)
        need = math.ceil(share * len(part))
        def verdict(ok): return "met" if ok else "NOT met"
        print(f"targets: plane count >= {need} of {len(part)}: {verdict(count_ok >= need)}; "
              f"normal median <= {med} deg: {verdict(statistics.median(normal_errs) <= med)}; "
              f"normal max <= {mx} deg: {verdict(max(normal_errs) <= mx)}; "
              f"centroid-plane <= {cd} mm: {verdict(max(dists) <= cd)}; "
              f"on the facet: {verdict(on_facet_all == matched_all)}")
    print(f"refused: {sum(refusals.values())} of {len(part)}" +
          "".join(f"\n  {n} x {why}" for why, n in sorted(refusals.items(), key=lambda kv: -kv[1])))

if real and len(stats) > 24:
    summary("first 24 scenes (the realistic set before the hard cases)", stats[:24])
    summary(f"scenes 24..{len(stats) - 1} (touching neighbours, the rock filling the ROI)", stats[24:])
summary(f"all {len(stats)} scenes", stats)
PY

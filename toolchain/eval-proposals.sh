#!/usr/bin/env bash
# Renders the simulator's multi-rock set (`petra sim set --multi`, or reuses
# it), runs `petra propose` on every whole pair (flight defaults, all
# kMaxProposals proposals), scores each with `petra score proposals`, and
# prints one row per scene plus the set's recall, precision and the best
# proposals' plane accuracy (docs/proposals.md, docs/performance.md).
#   toolchain/eval-proposals.sh [PETRA_BINARY] [WORK_DIR]
# e.g. toolchain/eval-proposals.sh build/release/sim/petra out/eval-scenes
# DISPARITY=truth replays each scene's disparity_truth.pfm in the candidates'
# chain runs (detection still matches): the back half's share of the misses.
set -euo pipefail
PETRA=${1:-build/release/sim/petra}
WORK=${2:-out/eval-scenes}
mkdir -p "$WORK"
SET="$WORK/multi-set"
if [ ! -f "$SET/done" ]; then
  # Scenes without the marker are someone else's (a held-out set): never render over them.
  if compgen -G "$SET/scene_*" > /dev/null; then
    echo "eval-proposals: $SET holds scenes but no 'done' file; refusing to render over them" \
         "(touch $SET/done to use them)" >&2
    exit 2
  fi
  "$PETRA" sim set --multi --out "$SET" > "$WORK/multi-set.log"
  touch "$SET/done"
fi
OUT="$WORK/multi-propose"
if [ "${DISPARITY:-}" = truth ]; then OUT="$WORK/multi-propose-truth"; fi
python3 - "$PETRA" "$SET" "$OUT" <<'PY'
import json, os, subprocess, sys, statistics
petra, set_dir, out_dir = sys.argv[1:4]
replay = os.environ.get("DISPARITY") == "truth"
tot = {"targets": 0, "targets_found": 0, "offered": 0, "offered_on_target": 0}
best_err, best_cpl, best_on, best_target, scenes = [], [], 0, 0, 0
print("| scene | proposals | targets found | offered on target | best: normal deg / centroid-plane mm / on facet |")
print("|---|---|---|---|---|")
for s in sorted(d for d in os.listdir(set_dir) if d.startswith("scene_") and os.path.isdir(os.path.join(set_dir, d))):
    sd, od = os.path.join(set_dir, s), os.path.join(out_dir, s)
    r = subprocess.run([petra, "propose", "--calib", f"{sd}/calib.json", "--left", f"{sd}/left.png",
                        "--right", f"{sd}/right.png", "--count", "8", "--out", od] +
                       (["--disparity", f"{sd}/disparity_truth.pfm"] if replay else []),
                       capture_output=True, text=True)
    scenes += 1
    if r.returncode != 0:
        print(f"| {s} | failed: {r.stderr.strip()[:90]} | | | |")
        continue
    sc = subprocess.run([petra, "score", "proposals", "--truth", f"{sd}/truth.json",
                         "--proposals", f"{od}/proposals.json", "--json"], capture_output=True, text=True)
    d = json.loads(sc.stdout)
    for k in tot: tot[k] += d[k]
    b = d.get("best")
    best = "none offered"
    if b:
        best_err.append(b["normal_error_deg"]); best_cpl.append(b["centroid_plane_mm"])
        best_on += 1 if b["on_facet"] else 0
        best_target += 1 if b["matches"] and b["target"] else 0
        best = f"{b['normal_error_deg']:.2f} / {b['centroid_plane_mm']:.2f} / {'yes' if b['on_facet'] else 'no'}" + \
               ("" if b["matches"] and b["target"] else " (not a target)")
    print(f"| {s} | {d['proposals']} | {d['targets_found']} of {d['targets']} | "
          f"{d['offered_on_target']} of {d['offered']} | {best} |")
rec = tot["targets_found"] / tot["targets"] if tot["targets"] else float("nan")
pre = tot["offered_on_target"] / tot["offered"] if tot["offered"] else float("nan")
print(f"\n{scenes} scenes: recall {rec:.3f} ({tot['targets_found']} of {tot['targets']} grindable, reachable facets), "
      f"precision {pre:.3f} ({tot['offered_on_target']} of {tot['offered']} offered planes)")
if best_err:
    print(f"best proposal's first offered plane: on a target facet {best_target} of {scenes}, normal error median "
          f"{statistics.median(best_err):.2f} max {max(best_err):.2f} deg, centroid-plane median "
          f"{statistics.median(best_cpl):.2f} max {max(best_cpl):.2f} mm, on its facet {best_on} of {len(best_err)}")
print(f"targets (issue 26): recall >= 0.90: {'met' if rec >= 0.9 else 'NOT met'}; precision >= 0.90: {'met' if pre >= 0.9 else 'NOT met'}")
PY

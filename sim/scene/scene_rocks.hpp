// The per-facet truth of a multi-rock scene (docs/scene.md "Several rocks"):
// could the flight chain's grinder work the facet, and does the arm reach it.
// Grindable: not hidden from either camera by another rock, facing the left
// camera within the chain's view limit, a disc of the grinder's diameter
// inside the exposed polygon, and the flattest disc of the rendered (rough,
// curved) surface within the flatness tolerance: the flight defaults of
// GrindParams{}. Every facet is judged so, the designed flat faces and the
// tangent planes of the rounded body alike: the renderer draws each as its
// plane plus the same relief. A disc beyond the tolerance is "too_curved"
// when the relief's bulge alone would be, else "too_rough". Reachable: algo/arm plan_approach from
// the stowed pose with the flight standoff (ApproachRequest{}), on the facet's centroid and outward
// normal in the world frame of calib.json; in a rock's truth (judge_rock), a grindable facet the
// arm cannot reach at its centroid is reachable when it reaches the centre of one of its discs
// within the flatness tolerance (the grinder works a disc, not the centroid).
#pragma once

#include <optional>
#include <vector>

#include "algo/arm/kinematics.hpp"
#include "algo/core/image_view.hpp"
#include "sim/scene/scene.hpp"
#include "sim/scene/scene_geometry.hpp"

namespace petra::sim {

struct FacetJudgement {
  bool grindable = false;
  const char* reason = "hidden";  // grindable|too_small|too_rough|too_curved|faces_away|hidden
  double disc_rms_mm = -1;        // flattest footprint disc's RMS (-1: not measured)
  bool reachable = false;
  arm::ArmReason reach = arm::ArmReason::ok;
  // Set when the centroid is out of reach but this grindable disc's centre
  // (local frame, on the face's plane) is not: judge_rock's disc search.
  std::optional<Eigen::Vector3d> reach_disc_centre;
};

// The flight defaults the truth is judged by (one definition each: GrindParams{}).
double grinder_diameter_mm();
double max_footprint_rms_mm();
double flight_standoff_mm();  // ApproachRequest{}: the arm's flight default

// Facet f of rock r (rock_at(); f.face indexes its faces; f.normal and
// f.centroid, local frame, are what truth.json says).
FacetJudgement judge_facet(const Scene& scene, int r, const VisibleFacet& f);

// True when a point of the facet (sampled every step_mm) is hidden from
// either camera by another rock of the scene.
bool facet_hidden(const Scene& scene, int r, const VisibleFacet& f, double step_mm);

// RMS about its own plane of the flattest disc of `diameter_mm` inside the
// exposed polygon of rock face `face` (the relief's surface below the
// plane); -1 when no disc fits. Stops at the first disc within stop_rms_mm.
double flattest_disc_rms_mm(const ConvexRock& rock, const FaceRelief& relief, int face,
                            double diameter_mm, double stop_rms_mm);

// The arm's verdict on a facet (local-frame centroid and outward normal).
arm::ArmReason facet_reach(const Scene& scene, const Eigen::Vector3d& centroid,
                           const Eigen::Vector3d& normal);

// A rough face's plane fitted (least squares) to surface points: the
// facet's normal, polygon (projected), centroid and area follow the fit.
struct FacetFit {
  bool fitted = false;
  double flatness_rms_mm = 0;  // RMS distance of the surface from that plane
  int points = 0;              // rectified left pixels that saw the face
};
FacetFit fit_facet(VisibleFacet& f, const std::vector<Eigen::Vector3d>& points);

// One rock's truth (truth.json "rocks").
struct RockTruth {
  Rect roi;  // original left image: the rock, its shadow and a margin
  std::optional<Eigen::Vector2i> click;
  double height_mm = 0;  // highest exposed point above the base ground
  double size_mm = 0;    // largest horizontal extent of the exposed part
  std::vector<VisibleFacet> facets;
  std::vector<FacetJudgement> judged;
};

// Rock r >= 1: its visible facets (fitted to the relief's surface when it is
// rough), judged, height and size; roi and click are the caller's
// (scene_truth.cpp, as for rock 0).
RockTruth further_rock_truth(const Scene& scene, int r);
// Judges every facet (a grindable facet out of reach at its centroid is
// reachable at a grindable disc the arm reaches, reach_disc_centre) and sets
// height and size (rock r's facets given).
void judge_rock(const Scene& scene, int r, RockTruth& truth);

// The centre (local frame) of a disc of the facet within the flatness
// tolerance that the arm reaches along the facet's normal; none: nullopt.
std::optional<Eigen::Vector3d> reachable_grindable_disc(const Scene& scene, int r,
                                                        const VisibleFacet& f);

}  // namespace petra::sim

// Grind planes (docs/method.md 4b) from the rock's mesh:
//   1. centroid, area and unit normal (AB x AC, turned towards the left
//      camera: a visible face's outward normal) of every rock triangle; for
//      the clustering, the mean of its vertices' smoothed normals when given
//      (at pixel spacing, AB x AC alone scatters by tens of degrees);
//   2. surface classification by C-means (eq. 9-12, algo/surface/cmeans) of the
//      normals: the paper's 4a clustering of 3-component samples, applied to
//      the normals as its 4b step asks, into cluster_count(c) > c classes
//      (Petra: a rock shows more faces than the c the operator wants, and c
//      classes would merge two faces into a plane of neither); it sees at most
//      kCMeansSamples triangles, a regular stride through the mesh (its cost
//      grows with samples x iterations; its output only seeds step 3);
//   3. refinement by angle clustering (algo/surface/angle_cluster) on the same
//      sample: the C-means class means are the initial centres (kept only if
//      more than 5 degrees apart, as the paper asks), then nearest-angle
//      assignment and area-weighted mean normals until no triangle changes
//      class; then every triangle of the mesh joins its nearest final centre.
//      C-means sees the shape of each class but can split one face along its
//      noise; the angle pass gives every triangle to the closest direction.
//      Petra adds: C-means can also leave two faces in one broad class (the
//      log-determinant term tolerates a wide class); while it lowers the
//      area-weighted angular dispersion by 2 %, the widest class is split in
//      two along the main direction of its normals' spread (in place of the
//      lightest class) and the angle pass is rerun;
//   4. per class (Petra adds): its largest edge-connected patch, a trimmed
//      total-least-squares plane through that patch's vertices (triangles more
//      than inlier_angle_deg off the plane normal or farther than 3 RMS are
//      dropped, twice); then the patch is regrown by position (grow_rounds
//      times: edge neighbours of any class within the 3-RMS band of the plane
//      and within grow_angle_deg of its normal join, and the plane is
//      refitted), because a matcher's error on a steep face (a staircase or a
//      bend) splits the face's normals into classes and one class's patch
//      leans; then the final plane from the patch's core (edge_rings rings of
//      triangles along its border left out: the matcher rounds every crease),
//      fitted by least squares along the viewing ray to the patch
//      (fit_along_ray: stereo measures depth, so that is where the error is;
//      total least squares tilts an oblique face away from the ray);
//      normal out of the rock, centroid (area-weighted mean of the core
//      triangles' centroids, on the plane), supporting area (whole patch),
//      RMS flatness and triangle count (a triangle regrown into two patches
//      at a crease counts for the first);
//      Classes whose planes agree within merge_angle_deg and whose centroids
//      lie within merge_distance_mm of each other's plane are merged (one face
//      split by the extra classes);
//   5. where the grinder sits (algo/surface/grind_qualify): the disc of the
//      tool's diameter on the face's patch where it sits flush, coming along
//      the face's normal (algo/surface/grind_footprint), its own plane and
//      flatness, and each plane's uncertainty from the stereo noise model
//      (algo/surface/plane_uncertainty). The reported plane is the face's
//      whole-patch normal through the disc's centre on the surface (with report_disc_plane,
//      the disc's own plane where it disagrees with the face's beyond the
//      noise). Verdicts, in
//      order: faces away (normal more than max_view_angle_deg from the
//      direction to the camera); too small (no covered disc of the tool's
//      diameter on the face); too rough (the flattest disc's RMS above
//      max_footprint_rms_mm); too uncertain (normal 1-sigma above
//      max_normal_sigma_deg or offset 1-sigma above max_offset_sigma_mm);
//      else grindable. Grindable planes are ranked by area, largest first, at
//      most c of them (the rest are surplus); rejected ones follow with their
//      reason. The whole patch's area and RMS are reported beside.
// Inputs: positions (world, mm), the rock triangles (neighbour links within
// this set, as keep_triangles leaves them), the left camera centre, c.
// Output: the result value; a plane index per triangle (0..count-1 in rank
// order, 0xFF for none) into a caller span. Scratch:
// grind_planes_scratch_bytes(triangles) from the arena, released on return.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <span>

#include "algo/core/arena.hpp"
#include "algo/core/result.hpp"
#include "algo/mesh/delaunay.hpp"
#include "algo/surface/angle_cluster.hpp"
#include "algo/surface/cmeans.hpp"
#include "algo/surface/grind_footprint.hpp"
#include "algo/surface/plane_uncertainty.hpp"

namespace petra {

inline constexpr std::size_t kCMeansSamples = 1024;

struct GrindParams {
  double grinder_diameter_mm = 20.0;    // the tool's footprint: a disc this wide must fit
  double max_view_angle_deg = 75.0;     // plane normal vs direction to the camera
  double max_footprint_rms_mm = 1.0;    // flatness tolerance: RMS over the footprint disc
  double min_footprint_coverage = 0.8;  // of the disc's area, by the face's triangles
  double max_normal_sigma_deg = 3.0;    // uncertainty limits of a grindable plane
  double max_offset_sigma_mm = 1.0;
  double sigma_disparity_px =
      kDisparitySigmaPx;      // matcher's disparity noise (the depth-noise model)
  double agree_sigmas = 3.0;  // disc plane vs face plane: the same within this
  // Report a disc's own plane where it disagrees with the face's (a face
  // curving at the tool's scale). Off: measured on the clean scene set, the
  // matcher's correlated errors tilt 20 mm discs of planar faces by up to
  // 12.8 deg beyond 3 sigma of the independent-noise model, while the face's
  // plane (photometrically refined) stays within 1.5 deg (docs/log.md).
  bool report_disc_plane = false;
  double inlier_angle_deg = 12.0;  // a triangle supports a plane within this angle
  double min_trim_band_mm = 0.3;   // floor of the 3-RMS distance band
  int edge_rings = 3;              // border rings left out of the final fit
  int grow_rounds = 2;             // regrowth of a patch by position (0: off)
  double grow_angle_deg = 25.0;    // a neighbour joins within this angle ...
  bool fit_along_ray = true;       // final fit: least squares along the viewing ray
  double merge_angle_deg = 8.0;    // two classes' planes this close in direction ...
  double merge_distance_mm = 3.0;  // ... and each centroid this near the other plane: merged
  CMeansParams cmeans;
  AngleClusterParams angle;
};

enum class PlaneVerdict : std::uint8_t {
  accepted,
  faces_away,
  too_small,
  too_rough,  // the flattest footprint disc is rougher than the tolerance
  no_support,
  surplus,  // qualified, but c larger ones did too
  too_uncertain,
  two_faces  // the class's patch spans two faces (a crease between them): no plane of its own
};
const char* verdict_name(PlaneVerdict v);

// Short machine name of a verdict (planes.json "verdict"): "grindable",
// "faces_away", "too_small", "too_rough", "too_uncertain", "no_support",
// "surplus", "two_faces".
const char* verdict_key(PlaneVerdict v);

struct GrindPlane {
  // Where the grinder goes: unit normal out of the rock, and the footprint
  // disc's centre on the surface (the patch centroid when no disc fits).
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d centroid_mm = Eigen::Vector3d::Zero();
  double area_mm2 = 0;  // whole patch
  double rms_mm = 0;    // whole patch, about its plane
  std::size_t triangles = 0;
  double view_angle_deg = 0;  // normal vs the direction to the camera
  PlaneVerdict verdict = PlaneVerdict::no_support;
  // The whole patch's own plane (normal, centroid on it).
  Eigen::Vector3d face_normal = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d face_centroid_mm = Eigen::Vector3d::Zero();
  // The footprint (algo/surface/grind_footprint): flatness of the best disc.
  double footprint_rms_mm = 0;
  double footprint_pv_mm = 0;
  double footprint_coverage = 0;
  Eigen::Vector3d footprint_normal = Eigen::Vector3d::UnitZ();  // the disc's own plane
  bool footprint_agrees = false;  // the disc's plane is the face's within agree_sigmas
  bool footprint_local = false;   // the reported plane is the disc's own (report_disc_plane)
  // Where the arm's reach left the disc (not_asked: the run knew no arm).
  FootprintReach footprint_reach = FootprintReach::not_asked;
  // 1-sigma of the reported plane (algo/surface/plane_uncertainty).
  double normal_sigma_deg = 0;
  double offset_sigma_mm = 0;
};

// The analyser reports '__i0', the compiler's own loop variable of the
// implicit copy over planes[], not a name of ours.
// NOLINTNEXTLINE(bugprone-reserved-identifier)
struct GrindResult {
  GrindPlane planes[kMaxClasses];    // accepted (ranked by area) then rejected
  int count = 0;                     // planes listed
  double footprint_diameter_mm = 0;  // the grinder's, as the planes were judged
  int accepted = 0;                  // the first `accepted` of them
  int classes = 0;                   // distinct faces left after merging
  int merges = 0;                    // classes merged as coplanar
  int splits = 0;                    // broad classes split (step 3)
  int cmeans_iterations = 0;
  int angle_iterations = 0;
  bool converged = false;  // both clusterings stopped because nothing moved
};

Status validate(const GrindParams& p);

// The merge rule: two planes (unit normal, point on it) are one face when the
// normals agree within p.merge_angle_deg and each point lies within
// p.merge_distance_mm of the other's plane.
bool same_plane(const Eigen::Vector3d& na, const Eigen::Vector3d& ca, const Eigen::Vector3d& nb,
                const Eigen::Vector3d& cb, const GrindParams& p);
// Classes clustered for c planes: min(8, max(c + 3, 2c)).
int cluster_count(int c);
std::size_t grind_planes_scratch_bytes(std::size_t triangles);

// The depth-noise model of the reported planes: the rig's focal length
// (px) and baseline (mm) with params.sigma_disparity_px. Zero focal length
// or baseline: unknown rig, the fit's residuals alone set the uncertainty.
struct RigGeometry {
  double focal_px = 0;
  double baseline_mm = 0;
  double correlation_px = 1;  // disparity errors shared over this box (the mean filter's)
};

// Angle between a plane's normal and the direction from its centroid to the
// camera centre, degrees (the faces-away verdict's measure).
double plane_view_angle_deg(const Eigen::Vector3d& normal, const Eigen::Vector3d& centroid_mm,
                            const Eigen::Vector3d& camera_centre_mm);

// point_normals: optional smoothed normals per point (algo/mesh/surface_normals);
// a triangle whose three vertices have one clusters by their mean, any
// other by its own AB x AC normal. Empty: AB x AC everywhere (the paper).
// reach: the arm's, when the caller knows it: each face's footprint disc is
// then one the tool reaches where the face has one (algo/surface/grind_footprint).
Result<GrindResult> find_grind_planes(
    std::span<const Eigen::Vector3d> xyz_mm, std::span<const MeshTriangle> rock_triangles,
    const Eigen::Vector3d& camera_centre_mm, int c, const GrindParams& params, Arena& scratch,
    std::span<std::uint8_t> triangle_plane, std::span<const Eigen::Vector3d> point_normals = {},
    const RigGeometry& rig = {}, const DiscReach* reach = nullptr);

}  // namespace petra

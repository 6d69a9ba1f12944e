// Where the grinder sits on a face: the best disc of the tool's diameter.
// Input: the face's samples (triangle centroids with their areas, world mm)
// and the face's plane (normal, centre), e.g. its whole-patch fit.
//   1. samples projected onto the face plane (frame e1, e2, n), binned by a
//      counting sort into square cells of at least the tool radius (at most
//      kFootprintCells cells);
//   2. candidate centres on a square grid over the samples' extent, spacing
//      radius / 2, widened until there are at most kFootprintCandidates;
//   3. per candidate, the samples within the tool radius of the centre
//      (distance in the face plane) are the disc: it must be covered (the
//      samples' area at least min_coverage of pi r^2, and each of the disc's
//      8 sectors at least half its share: a disc over the face's edge or a
//      hole is not one the tool can sit on); a least-squares plane of the
//      offsets along n (area-weighted) gives the disc's own plane, and the
//      area-weighted RMS of the offsets about it is the disc's flatness;
//   4. the best disc: of the covered discs flat within the tolerance
//      (max_rms_mm), the one whose samples lie closest to a plane parallel
//      to the face's (least RMS of their offsets along the face normal):
//      the grinder comes along the face's normal, so that is where it sits
//      flush; on a curved face, where the surface is parallel to the face's
//      plane. With a reach (the arm's, from the caller), the most level of
//      those the tool reaches along the face's normal: a flush disc out of
//      the arm's reach is no place to grind when another flat one is in it;
//      none reached, the most level all the same (the caller's own reach
//      check then says the plane is out of reach). None within the
//      tolerance: the flattest (the face is too rough, and the verdict says
//      so);
//   5. the best disc refitted on every sample in it (the search may thin a
//      large face to kFootprintSamples samples) and its peak-to-valley.
// Flatness is the RMS over the footprint, not the peak-to-valley: the
// peak-to-valley of N noisy samples grows with N and follows the single worst
// mismatch, so it measures the matcher; the RMS estimates the surface's
// deviation with a known noise floor. The peak-to-valley is reported beside.
// Cost: O(m) for binning plus at most kFootprintCandidates discs, each
// visiting the samples of the cells it overlaps (a thinned face holds at
// most kFootprintSamples); then one O(m) refit. Scratch:
// footprint_scratch_bytes(m) from the arena, released on return. No heap.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <span>

#include "algo/core/arena.hpp"
#include "algo/core/result.hpp"
#include "algo/mesh/delaunay.hpp"

namespace petra {

inline constexpr std::size_t kFootprintCandidates = 256;
inline constexpr std::size_t kFootprintCells = 4096;
inline constexpr std::size_t kFootprintSamples = 8192;

// 32 bytes: the areas in float (7 digits for areas of 0.01..100 mm^2), so
// that the samples of every triangle take no more than a point and a double.
struct FaceSample {
  Eigen::Vector3d p;  // world mm (a triangle's centroid)
  float area = 0;     // mm^2
  // mm^2 across the left camera's ray: the triangle's area times |cos| of its
  // own normal to the ray, what its pixels cover at its range; 0 when not known.
  float seen = 0;
};
static_assert(sizeof(FaceSample) == 32, "a face sample per mesh triangle: keep it small");

// Whether the tool reaches a disc: its centre on the surface, the tool coming
// along `normal` (unit, out of the rock). The arm's plan implements it
// (algo/propose/arm_reach); the footprint only asks.
class DiscReach {
 public:
  virtual bool reaches(const Eigen::Vector3d& centre_mm, const Eigen::Vector3d& normal) const = 0;

 protected:
  DiscReach() = default;
  DiscReach(const DiscReach&) = default;
  DiscReach& operator=(const DiscReach&) = default;
  ~DiscReach() = default;
};

// Where a reach left the footprint's disc (what the operator is told).
enum class FootprintReach : std::uint8_t {
  not_asked = 0,     // no reach given, or no disc within the flatness tolerance
  most_level = 1,    // the most level flat disc, which the arm reaches
  moved = 2,         // the most level flat disc is out of reach: the most level one reached
  none_reached = 3,  // the arm reaches no flat disc: the most level all the same
};
// "most_level", "moved", "none_reached" (planes.json); "" for not_asked.
const char* footprint_reach_key(FootprintReach r);

struct FootprintParams {
  double diameter_mm = 20.0;
  double min_coverage = 0.8;  // of the disc's area, by the samples in it
  double max_rms_mm = 1.0;    // flatness tolerance: only discs within it are chosen for flushness
  const DiscReach* reach = nullptr;  // the caller's; none: every disc is reachable
};

struct Footprint {
  bool covered = false;  // some disc of the tool's size lies on the face
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();    // the disc's plane, same side as the face's
  Eigen::Vector3d centre_mm = Eigen::Vector3d::Zero();  // on the disc's plane
  double rms_mm = 0;                                    // flatness over the disc
  double peak_to_valley_mm = 0;                         // over the disc, about its plane
  double coverage = 0;                                  // sample area / disc area
  std::size_t samples = 0;                              // in the disc
  int candidates = 0;                                   // discs tried
  FootprintReach reach = FootprintReach::not_asked;
};

// A mesh triangle (vertex indices into xyz_mm) as a sample: centroid, area
// and the area it shows the camera (centre camera_mm, world mm).
FaceSample triangle_sample(std::span<const Eigen::Vector3d> xyz_mm, const MeshTriangle& t,
                           const Eigen::Vector3d& camera_mm);

std::size_t footprint_scratch_bytes(std::size_t samples);

// face_normal: unit; face_centre: a point of the face plane near the face's
// middle. Fails on bad parameters or fewer than 3 samples.
Result<Footprint> find_footprint(std::span<const FaceSample> samples,
                                 const Eigen::Vector3d& face_normal,
                                 const Eigen::Vector3d& face_centre, const FootprintParams& params,
                                 Arena& scratch);

// The samples of a face within radius_mm of `centre` measured in the plane
// with normal n (the footprint's disc), for the caller's own sums.
template <class Fn>
void for_each_in_disc(std::span<const FaceSample> samples, const Eigen::Vector3d& n,
                      const Eigen::Vector3d& centre, double radius_mm, Fn&& fn) {
  const double r2 = radius_mm * radius_mm;
  for (const FaceSample& s : samples) {
    const Eigen::Vector3d q = s.p - centre;
    const double along = q.dot(n);
    if (q.squaredNorm() - along * along <= r2) fn(s);
  }
}

}  // namespace petra

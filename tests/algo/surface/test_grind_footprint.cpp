#include "algo/surface/grind_footprint.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <functional>
#include <random>
#include <utility>
#include <vector>

#include "tests/support/angles.hpp"
#include "tests/support/heap_counter.hpp"

namespace petra {
namespace {

// A face in the plane through `o` with normal n (frame e1, e2), meshed on a
// 0.5 mm grid of w x h mm, each cell two triangles; height(x, y) moves the
// surface along n. The samples are the triangles' centroids and areas.
struct FaceMesh {
  Eigen::Vector3d o, n, e1, e2;
  std::vector<FaceSample> samples;
  Eigen::Vector3d at(double x, double y, double z) const { return o + x * e1 + y * e2 + z * n; }
};

FaceMesh make_relief_face(double w, double h, const std::function<double(double, double)>& height,
                          const std::function<bool(double, double)>& keep = nullptr) {
  FaceMesh f;
  f.o = Eigen::Vector3d(10, -20, 900);
  f.n = Eigen::Vector3d(0.2, -0.3, -1).normalized();
  f.e1 = Eigen::Vector3d::UnitY().cross(f.n).normalized();
  f.e2 = f.n.cross(f.e1);
  const double s = 0.5;
  auto p = [&](double x, double y) { return f.at(x, y, height(x, y)); };
  for (double y = -h / 2; y < h / 2 - 1e-9; y += s)
    for (double x = -w / 2; x < w / 2 - 1e-9; x += s) {
      if (keep && !keep(x + s / 2, y + s / 2)) continue;
      const Eigen::Vector3d a = p(x, y), b = p(x + s, y), c = p(x + s, y + s), d = p(x, y + s);
      f.samples.push_back({(a + b + c) / 3, static_cast<float>(0.5 * (b - a).cross(c - a).norm())});
      f.samples.push_back({(a + c + d) / 3, static_cast<float>(0.5 * (c - a).cross(d - a).norm())});
    }
  return f;
}

Result<Footprint> run_footprint(const FaceMesh& f, double diameter,
                                const DiscReach* reach = nullptr) {
  std::vector<std::byte> block(footprint_scratch_bytes(f.samples.size()));
  Arena arena(block);
  FootprintParams p;
  p.diameter_mm = diameter;
  p.reach = reach;
  auto r = find_footprint(f.samples, f.n, f.o, p, arena);
  EXPECT_EQ(arena.used(), 0u);
  return r;
}

TEST(GrindFootprint, FlatCornerOfARoughFaceIsFound) {
  // 60 x 40 mm: rough (1 mm RMS relief) except a flat 25 x 25 mm corner
  // tilted 2 deg about e2 and raised 0.5 mm: the tool sits there.
  std::mt19937 rng(2);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> relief(200000);
  for (double& v : relief) v = g(rng);
  const double tilt = std::tan(2.0 * M_PI / 180.0);
  auto flat = [](double x, double y) { return x >= 5 && y >= -20 && y <= 5; };
  auto height = [&](double x, double y) {
    if (flat(x, y)) return 0.5 + tilt * (x - 17.5);
    const auto i =
        static_cast<std::size_t>((x + 30) * 2) * 101 + static_cast<std::size_t>((y + 20) * 2);
    return relief[i % relief.size()];
  };
  const FaceMesh f = make_relief_face(60, 40, height);
  auto r = run_footprint(f, 20);
  ASSERT_TRUE(r.ok()) << r.error().message;
  ASSERT_TRUE(r->covered);
  // The disc lies in the flat corner (its centre at least a radius inside).
  const Eigen::Vector3d q = r->centre_mm - f.o;
  const double x = q.dot(f.e1), y = q.dot(f.e2);
  EXPECT_GE(x, 15 - 0.3);
  EXPECT_LE(y, -5 + 0.3);
  EXPECT_LT(r->rms_mm, 0.01);
  EXPECT_LT(r->peak_to_valley_mm, 0.05);
  // Its plane is the corner's: 2 deg from the face frame about e2, on it.
  const Eigen::Vector3d corner_n = (f.n - tilt * f.e1).normalized();
  EXPECT_LT(test::angle_deg(r->normal, corner_n), 0.05);
  EXPECT_NEAR(q.dot(f.n), 0.5 + tilt * (x - 17.5), 0.01);
  EXPECT_GT(r->coverage, 0.95);
  EXPECT_LE(r->candidates, static_cast<int>(kFootprintCandidates));
}

// A spherical cap of radius kCapRadiusMm, its apex at (4, -3) in the face frame.
constexpr double kCapRadiusMm = 300;
double cap_height(double x, double y) {
  const double rho2 = (x - 4) * (x - 4) + (y + 3) * (y + 3);
  return kCapRadiusMm - std::sqrt(kCapRadiusMm * kCapRadiusMm - rho2);
}

TEST(GrindFootprint, CurvedFaceGivesTheDiscWhereItIsParallelToTheFacePlane) {
  // A spherical cap, radius of curvature 300 mm, apex at (4, -3) in the face
  // frame: every disc is as flat as another about its own plane, and the
  // one at the apex lies level with the face's plane: the grinder, coming
  // along the face's normal, sits flush there. Its plane is the sphere's
  // tangent plane at its centre.
  const double R = kCapRadiusMm;
  const auto height = cap_height;
  const FaceMesh f = make_relief_face(50, 50, height);
  auto r = run_footprint(f, 20);
  ASSERT_TRUE(r.ok());
  ASSERT_TRUE(r->covered);
  const Eigen::Vector3d q = r->centre_mm - f.o;
  const double x = q.dot(f.e1), y = q.dot(f.e2);
  // Sphere normal under the disc's centre (pointing the face normal's way).
  const Eigen::Vector3d centre_of_sphere = f.at(4, -3, R);
  const Eigen::Vector3d surface = f.at(x, y, height(x, y));
  const Eigen::Vector3d tangent_n = (centre_of_sphere - surface).normalized();
  EXPECT_LT(test::angle_deg(r->normal, tangent_n), 0.15);
  // The candidates lie 5 mm apart: the nearest to the apex is within 3.6 mm.
  EXPECT_LT(std::hypot(x - 4, y + 3), 3.6);
  EXPECT_LT(test::angle_deg(r->normal, f.n), 0.7);
  // Its centre on the surface (on the disc's own plane: over a 10 mm radius
  // the cap's mean lies r^2 / 4R = 0.08 mm above the point), not on the face's.
  EXPECT_NEAR(q.dot(f.n), height(x, y) + 100.0 / (4 * R), 0.01);
  // RMS of a paraboloid over a disc about its best plane: r^2 / (2 R sqrt 12).
  EXPECT_NEAR(r->rms_mm, 100.0 / (2 * R * std::sqrt(12.0)), 0.01);
}

TEST(GrindFootprint, ALevelDiscWithinTheToleranceWinsOverAFlatterTiltedOne) {
  // 60 x 40 mm: the half x < 0 a perfectly flat plane tilted 6 deg from the
  // face's, the half x >= 0 level with 0.2 mm of relief. The tilted half is
  // the flatter about its own plane, but a tool coming along the face's
  // normal sits flush on the level half; when the level half is rougher
  // than the tolerance, the flattest disc is the one (the face too rough).
  const double tilt = std::tan(6.0 * M_PI / 180.0);
  const auto face = [&](double amplitude) {
    return make_relief_face(60, 40, [=](double x, double y) {
      return x < 0 ? tilt * x : amplitude * std::sin(2.3 * x) * std::cos(1.9 * y);
    });
  };
  const auto side = [](const FaceMesh& f, const Footprint& fp) {
    return (fp.centre_mm - f.o).dot(f.e1);
  };
  const FaceMesh level = face(0.4);  // RMS 0.2 mm
  auto r = run_footprint(level, 20);
  ASSERT_TRUE(r.ok());
  ASSERT_TRUE(r->covered);
  EXPECT_GE(side(level, *r), 10 - 2.6);
  EXPECT_LT(r->rms_mm, 1.0);
  EXPECT_LT(test::angle_deg(r->normal, level.n), 1.0);
  const FaceMesh rough = face(3.0);  // RMS 1.5 mm, over the 1 mm tolerance
  r = run_footprint(rough, 20);
  ASSERT_TRUE(r.ok());
  ASSERT_TRUE(r->covered);
  EXPECT_LE(side(rough, *r), -10 + 2.6);
  EXPECT_LT(r->rms_mm, 0.01);
}

// A reach the test draws: the discs whose centre (in the face frame) passes
// `inside`, asked along the face's normal; keeps what it is asked.
class DrawnReach final : public DiscReach {
 public:
  DrawnReach(const FaceMesh& f, std::function<bool(double, double)> inside)
      : f_(f), inside_(std::move(inside)) {}
  bool reaches(const Eigen::Vector3d& centre_mm, const Eigen::Vector3d& normal) const override {
    ++asked;
    asked_at.push_back(centre_mm);
    if (test::angle_deg(normal, f_.n) > 1e-6) ++off_normal;
    const Eigen::Vector3d q = centre_mm - f_.o;
    return inside_(q.dot(f_.e1), q.dot(f_.e2));
  }
  // No disc asked twice (candidate centres lie millimetres apart).
  bool each_once() const {
    for (std::size_t i = 0; i < asked_at.size(); ++i)
      for (std::size_t j = 0; j < i; ++j)
        if ((asked_at[i] - asked_at[j]).norm() < 1.0) return false;
    return true;
  }
  mutable int asked = 0;
  mutable int off_normal = 0;
  mutable std::vector<Eigen::Vector3d> asked_at;

 private:
  const FaceMesh& f_;
  std::function<bool(double, double)> inside_;
};

TEST(GrindFootprint, AReachMovesTheDiscToTheMostLevelOneTheArmReaches) {
  // The cap of CurvedFaceGivesTheDiscWhereItIsParallelToTheFacePlane: the
  // most level disc is at the apex (4, -3). An arm that reaches only x > 12
  // gets the most level disc there: the nearest to the apex beyond the wall.
  const double R = kCapRadiusMm;
  const auto height = cap_height;
  const FaceMesh f = make_relief_face(50, 50, height);
  const auto at = [&](const Footprint& fp) {
    const Eigen::Vector3d q = fp.centre_mm - f.o;
    return std::pair{q.dot(f.e1), q.dot(f.e2)};
  };
  auto free = run_footprint(f, 20);
  ASSERT_TRUE(free.ok() && free->covered);
  EXPECT_EQ(free->reach, FootprintReach::not_asked);

  const DrawnReach wall(f, [](double x, double) { return x > 12; });
  auto r = run_footprint(f, 20, &wall);
  ASSERT_TRUE(r.ok() && r->covered);
  EXPECT_EQ(r->reach, FootprintReach::moved);
  EXPECT_EQ(wall.off_normal, 0) << "the tool comes along the face's normal";
  EXPECT_TRUE(wall.each_once());
  const auto [x, y] = at(*r);
  EXPECT_GT(x, 12);
  // Candidates lie 5 mm apart: the first beyond the wall is within 5 mm of
  // it, near the apex's row (within half the grid's diagonal, as the free
  // disc is of the apex).
  EXPECT_LT(x, 12 + 5.01);
  EXPECT_LT(std::abs(y + 3), 3.6);
  EXPECT_GT(wall.asked, 1);
  // Its centre on the surface there, as the free disc's is at the apex.
  EXPECT_NEAR((r->centre_mm - f.o).dot(f.n), height(x, y) + 100.0 / (4 * R), 0.01);

  // The most level disc reached: one question, the same disc as without a reach.
  const DrawnReach everywhere(f, [](double, double) { return true; });
  r = run_footprint(f, 20, &everywhere);
  ASSERT_TRUE(r.ok() && r->covered);
  EXPECT_EQ(everywhere.asked, 1);
  EXPECT_EQ(r->reach, FootprintReach::most_level);
  EXPECT_LT((r->centre_mm - free->centre_mm).norm(), 1e-9);

  // None reached: every flat disc asked once, then the most level all the same.
  const DrawnReach nowhere(f, [](double, double) { return false; });
  r = run_footprint(f, 20, &nowhere);
  ASSERT_TRUE(r.ok() && r->covered);
  EXPECT_EQ(r->reach, FootprintReach::none_reached);
  EXPECT_TRUE(nowhere.each_once());
  EXPECT_GT(nowhere.asked, 1);
  EXPECT_LE(nowhere.asked, r->candidates);
  EXPECT_LT((r->centre_mm - free->centre_mm).norm(), 1e-9);
}

TEST(GrindFootprint, AReachIsNotAskedOfDiscsRougherThanTheTolerance) {
  // The level half of ALevelDiscWithinTheToleranceWinsOverAFlatterTiltedOne
  // rougher than the tolerance: the flat discs are the tilted half's, and an
  // arm that reaches only the level half is never asked of it.
  const double tilt = std::tan(6.0 * M_PI / 180.0);
  const FaceMesh f = make_relief_face(60, 40, [=](double x, double y) {
    return x < 0 ? tilt * x : 3.0 * std::sin(2.3 * x) * std::cos(1.9 * y);
  });
  int level_half_asked = 0;
  const DrawnReach level_half(f, [&](double x, double) {  // 3/4 of a disc there is rough
    level_half_asked += x > 5 ? 1 : 0;
    return x > 5;
  });
  auto r = run_footprint(f, 20, &level_half);
  ASSERT_TRUE(r.ok() && r->covered);
  EXPECT_EQ(r->reach, FootprintReach::none_reached);
  EXPECT_GT(level_half.asked, 0);
  EXPECT_EQ(level_half_asked, 0) << "a disc over the tolerance is no place to grind";
  EXPECT_LT(r->rms_mm, 0.01);  // the flattest, as without a reach
}

TEST(GrindFootprint, FaceSmallerThanTheToolIsNotCovered) {
  const FaceMesh f = make_relief_face(15, 40, [](double, double) { return 0.0; });
  auto r = run_footprint(f, 20);
  ASSERT_TRUE(r.ok());
  EXPECT_FALSE(r->covered);
  // A face wide enough, but holed in the middle, with a band around: no
  // covered disc either.
  const FaceMesh holed = make_relief_face(
      30, 30, [](double, double) { return 0.0; },
      [](double x, double y) { return std::hypot(x, y) > 6; });
  r = run_footprint(holed, 20);
  ASSERT_TRUE(r.ok());
  EXPECT_FALSE(r->covered);
  // The same face with the tool of 12 mm: a disc fits in the band's corner.
  r = run_footprint(holed, 12);
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(r->covered);
}

TEST(GrindFootprint, BadInputIsNamed) {
  const FaceMesh f = make_relief_face(30, 30, [](double, double) { return 0.0; });
  std::vector<std::byte> block(footprint_scratch_bytes(f.samples.size()));
  Arena arena(block);
  FootprintParams p;
  p.diameter_mm = 0;
  auto r = find_footprint(f.samples, f.n, f.o, p, arena);
  EXPECT_EQ(r.code(), Errc::invalid_argument);
  EXPECT_NE(std::string(r.error().message).find("diameter_mm"), std::string::npos);
  EXPECT_EQ(find_footprint(f.samples, 2 * f.n, f.o, {}, arena).code(), Errc::invalid_argument);
  EXPECT_EQ(find_footprint(std::span(f.samples).first(2), f.n, f.o, {}, arena).code(),
            Errc::degenerate);
  std::vector<std::byte> small(64);
  Arena tiny(small);
  EXPECT_EQ(find_footprint(f.samples, f.n, f.o, {}, tiny).code(), Errc::capacity_exceeded);
}

TEST(GrindFootprint, LargeFaceIsBoundedAndHeapFree) {
  // 150 x 150 mm at 0.5 mm: 180000 samples, thinned for the search.
  const FaceMesh f =
      make_relief_face(150, 150, [](double x, double y) { return 0.001 * x * y / 100; });
  std::vector<std::byte> block(footprint_scratch_bytes(f.samples.size()));
  Arena arena(block);
  test::HeapScope scope;
  auto r = find_footprint(f.samples, f.n, f.o, {}, arena);
  EXPECT_EQ(scope.allocations(), 0u);
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(r->covered);
  EXPECT_LE(r->candidates, static_cast<int>(kFootprintCandidates));
  EXPECT_LE(footprint_scratch_bytes(f.samples.size()), footprint_scratch_bytes(kFootprintSamples));
}

}  // namespace
}  // namespace petra

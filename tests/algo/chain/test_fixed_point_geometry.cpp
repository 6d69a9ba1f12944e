// The geometry written over a scalar type, instantiated with the Q formats of
// algo/surface/fixed_point.hpp and compared with double on simulated scenes (ray-cast
// ridge rocks seen by a Bumblebee2-like rig, 0.1 px disparity noise): eq. 8
// triangulation, the rock/ground segmentation with its plane fit, C-means and
// the angle clustering. The bounds asserted here are the figures quoted in
// docs/reconstruction.md; the test prints the measured values.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "algo/chain/reconstruction.hpp"
#include "algo/mesh/triangulate.hpp"
#include "algo/surface/angle_cluster.hpp"
#include "algo/surface/cmeans.hpp"
#include "algo/surface/fixed_point.hpp"
#include "algo/surface/ground_segment.hpp"
#include "tests/support/angles.hpp"
#include "tests/support/synthetic_disparity.hpp"
#include "tests/support/test_rig.hpp"

namespace petra {
namespace {

template <class Q>
using QVec3 = Eigen::Matrix<Q, 3, 1>;

struct SceneData {
  StereoRig rig;
  RectifiedPair pair;
  test::SyntheticDisparity disp;
  std::vector<Eigen::Vector2d> left_px, right_px;  // original pixels per point
  std::vector<Eigen::Vector3d> xyz;                // double triangulation
  std::vector<PixelPos> px;
  ReconstructionOutput recon;
  std::vector<std::byte> arena_block;
};

// One simulated scene, reconstructed in double by the real chain.
SceneData make_scene(std::uint64_t seed) {
  SceneData s;
  s.rig = test::looking_rig(seed);
  s.pair = *rectify_geometry(s.rig, 1024, 768);
  const Rect roi = test::rock_box(s.pair, test::ridge_rock(), 40, 30, 55, 30);
  s.disp = test::render_disparity(s.pair, roi, test::ridge_rock(), 0.1, seed);
  ReconstructionBudget budget{roi.w, roi.h, static_cast<std::size_t>(roi.w) * roi.h};
  s.arena_block.resize(reconstruction_arena_bytes(budget));
  Arena arena(s.arena_block);
  ReconstructionRequest req;
  req.planes = 3;
  StepTimings t;
  auto r = reconstruct(s.rig, s.pair, s.disp.view(), req, {}, budget, arena, {}, t);
  EXPECT_TRUE(r.ok()) << r.error().message;
  s.recon = *r;
  for (std::size_t i = 0; i < s.recon.xyz_mm.size(); ++i) {
    const PixelPos p = s.recon.pixels[i];
    const std::int16_t q = s.recon.filtered.q4(p.u - roi.x, p.v - roi.y);
    s.left_px.push_back(*rectified_to_original(s.rig.left, s.pair.left, {p.u + 0.0, p.v + 0.0}));
    s.right_px.push_back(
        *rectified_to_original(s.rig.right, s.pair.right, {p.u - disparity_px(q), p.v + 0.0}));
    s.xyz.push_back(s.recon.xyz_mm[i]);
    s.px.push_back(p);
  }
  return s;
}

const std::vector<SceneData>& scenes() {
  static const std::vector<SceneData> all = [] {
    std::vector<SceneData> v;
    for (std::uint64_t seed : {1u, 2u, 3u}) v.push_back(make_scene(seed));
    return v;
  }();
  return all;
}

template <class Q>
double triangulation_error_mm(const SceneData& s) {
  const auto l = eq8_camera<Q>(s.rig.left), r = eq8_camera<Q>(s.rig.right);
  const auto ld = eq8_camera<double>(s.rig.left), rd = eq8_camera<double>(s.rig.right);
  double worst = 0;
  for (std::size_t i = 0; i < s.left_px.size(); ++i) {
    const Vec2T<Q> ul(Q(s.left_px[i].x()), Q(s.left_px[i].y()));
    const Vec2T<Q> ur(Q(s.right_px[i].x()), Q(s.right_px[i].y()));
    auto pq = triangulate_eq8<Q>(l, r, ul, ur);
    auto pd = triangulate_eq8<double>(ld, rd, s.left_px[i], s.right_px[i]);
    EXPECT_TRUE(pq.ok() && pd.ok());
    const Eigen::Vector3d diff(to_double((*pq)(0)) - pd->x(), to_double((*pq)(1)) - pd->y(),
                               to_double((*pq)(2)) - pd->z());
    worst = std::max(worst, diff.norm());
  }
  return worst;
}

TEST(FixedPointGeometry, TriangulationMatchesDouble) {
  for (const SceneData& s : scenes()) {
    const double e32 = triangulation_error_mm<Q31_32>(s);
    const double e16 = triangulation_error_mm<Q47_16>(s);
    std::printf("eq. 8 over %zu points: Q31.32 max %.3g mm, Q47.16 max %.3g mm\n", s.left_px.size(),
                e32, e16);
    EXPECT_LT(e32, 1e-5);
    EXPECT_LT(e16, 0.25);
  }
}

template <class Q>
void compare_segmentation(const SceneData& s, double max_angle_deg, double max_d_mm,
                          double max_label_share) {
  std::vector<QVec3<Q>> xyz;
  for (const auto& p : s.xyz) xyz.push_back(QVec3<Q>(Q(p.x()), Q(p.y()), Q(p.z())));
  const Eigen::Vector3d c = camera_centre_world(s.rig.left);
  const QVec3<Q> cq(Q(c.x()), Q(c.y()), Q(c.z()));
  std::vector<PointClass> lq(xyz.size()), ld(xyz.size());
  auto gq = segment_ground<Q>(xyz, s.px, s.disp.roi, {}, cq, GroundParams{}, lq);
  auto gd = segment_ground<double>(s.xyz, s.px, s.disp.roi, {}, c, GroundParams{}, ld);
  ASSERT_TRUE(gq.ok()) << gq.error().message;
  ASSERT_TRUE(gd.ok());
  const Eigen::Vector3d nq(to_double(gq->plane.normal(0)), to_double(gq->plane.normal(1)),
                           to_double(gq->plane.normal(2)));
  const double angle = test::angle_deg(nq, gd->plane.normal);
  const double dd = std::abs(to_double(gq->plane.d) - gd->plane.d);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < lq.size(); ++i) differ += lq[i] != ld[i];
  const double share = static_cast<double>(differ) / static_cast<double>(lq.size());
  std::printf("segmentation (%zu points): plane %.3g deg, d %.3g mm, labels differ %.3g %%\n",
              lq.size(), angle, dd, 100 * share);
  EXPECT_LT(angle, max_angle_deg);
  EXPECT_LT(dd, max_d_mm);
  EXPECT_LE(share, max_label_share);
}

TEST(FixedPointGeometry, GroundSegmentationMatchesDouble) {
  for (const SceneData& s : scenes()) {
    compare_segmentation<Q31_32>(s, 1e-4, 1e-3, 1e-4);
    compare_segmentation<Q47_16>(s, 0.05, 0.05, 2e-3);
  }
}

TEST(FixedPointGeometry, ClusteringMatchesDouble) {
  using Q = Q31_32;
  for (const SceneData& s : scenes()) {
    // The smoothed normals of the rock points: what grind_planes clusters.
    std::vector<Eigen::Vector3d> nd;
    for (std::size_t i = 0; i < s.recon.normals.size(); i += 7)
      if (s.recon.point_class[i] == PointClass::rock && s.recon.normals[i].squaredNorm() > 0)
        nd.push_back(s.recon.normals[i]);
    ASSERT_GT(nd.size(), 300u);
    std::vector<QVec3<Q>> nq;
    for (const auto& v : nd) nq.push_back(QVec3<Q>(Q(v.x()), Q(v.y()), Q(v.z())));
    std::vector<std::uint8_t> cd(nd.size()), cq(nd.size());
    auto rd = cmeans<double>(nd, 3, CMeansParams{}, cd);
    auto rq = cmeans<Q>(nq, 3, CMeansParams{}, cq);
    ASSERT_TRUE(rd.ok() && rq.ok());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < cd.size(); ++i) differ += cd[i] != cq[i];
    double centre = 0;
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d mq(to_double(rq->classes[j].mean(0)), to_double(rq->classes[j].mean(1)),
                               to_double(rq->classes[j].mean(2)));
      centre = std::max(centre, (mq - rd->classes[j].mean).norm());
    }
    // Angle clustering from the double C-means centres.
    std::vector<double> w(nd.size(), 1.0);
    std::vector<Q> wq(nd.size(), Q(1));
    Eigen::Vector3d init[3];
    QVec3<Q> init_q[3];
    for (int j = 0; j < 3; ++j) {
      init[j] = rd->classes[j].mean;
      init_q[j] = QVec3<Q>(Q(init[j].x()), Q(init[j].y()), Q(init[j].z()));
    }
    std::vector<std::uint8_t> ad(nd.size()), aq(nd.size());
    auto ard = angle_cluster<double>(nd, w, std::span<const Eigen::Vector3d>(init, 3), {}, ad);
    auto arq = angle_cluster<Q>(nq, wq, std::span<const QVec3<Q>>(init_q, 3), {}, aq);
    ASSERT_TRUE(ard.ok() && arq.ok());
    ASSERT_EQ(ard->c, arq->c);
    std::size_t adiffer = 0;
    for (std::size_t i = 0; i < ad.size(); ++i) adiffer += ad[i] != aq[i];
    double angle = 0;
    for (int j = 0; j < ard->c; ++j) {
      const Eigen::Vector3d cq3(to_double(arq->centres[j](0)), to_double(arq->centres[j](1)),
                                to_double(arq->centres[j](2)));
      angle = std::max(angle, test::angle_deg(cq3, ard->centres[j]));
    }
    std::printf(
        "c-means (%zu normals): labels differ %zu, centres %.3g; angle clustering: labels differ "
        "%zu, "
        "centres %.3g deg\n",
        nd.size(), differ, centre, adiffer, angle);
    EXPECT_EQ(rq->iterations, rd->iterations);
    EXPECT_LE(differ, nd.size() / 1000);
    EXPECT_LT(centre, 1e-6);
    EXPECT_LE(adiffer, nd.size() / 1000);
    EXPECT_LT(angle, 1e-4);
  }
}

}  // namespace
}  // namespace petra

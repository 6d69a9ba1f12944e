// A rig that drifted after its calibration: the right camera pitched by
// 0.1 deg about its own x axis, while calib.json still holds the old pose
// (realistic set entry 14, two faces). The rectified rows then differ by
// about 1.9 px; the DP matches along rows, so uncorrected the chain loses the
// ground and refuses the pair. The calibration check measures the offset and
// the chain rectifies the right view again with its rows moved by it
// (Rectifier::rectify_rows_moved): the faces come back within the realistic
// targets, and an aligned pair is left as it is. The same pair checks the
// DP's gray-level map against the cameras' gain and offset. Rendered only where the chain
// reads (see test_eval_roi_fill).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>

#include "algo/chain/pipeline.hpp"
#include "sim/scene/scene_set.hpp"
#include "tests/support/rendered_scene.hpp"
#include "tests/support/scene_chain_run.hpp"

namespace petra {
namespace {

const test::RenderedScene& drift_scene() {
  static const test::RenderedScene f = [] {
    sim::SceneOptions o = sim::real_scene_set()[14];
    o.edge_supersampling = 2;
    return test::render_for_test(o, 48);
  }();
  return f;
}

// The calibration as it was: the right camera pitched back by `deg` about
// its own x axis (its centre kept).
StereoRig drifted(StereoRig rig, double deg) {
  const Eigen::Matrix3d pitch =
      Eigen::AngleAxisd(deg * M_PI / 180.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
  rig.right.R = pitch * rig.right.R;
  rig.right.T_mm = pitch * rig.right.T_mm;
  return rig;
}

// The chain given `rig` on the fixture with the truth's ROI and c.
test::SceneChainRun run_with_rig(const test::RenderedScene& f, const StereoRig& rig,
                                 const PipelineParams& params) {
  return test::run_chain_on_scene(f, rig, params, 256, false);
}

// The DP's gray-level map (measured on its edge pairs) against the cameras
// that rendered the pair: left level = (g_L / g_R)(right level - o_R) + o_L,
// compared at mid-gray; vignetting and noise make it approximate.
void expect_gray_map_undoes_the_cameras(const MatchDpStats& m, const sim::World& w) {
  const double gain = w.gain_left / w.gain_right;
  const double truth_mid = gain * (128.0 - w.offset_right_dn) + w.offset_left_dn;
  const double mid = (m.gray_gain_q8 * 128.0 + m.gray_offset_q8) / 256.0;
  std::printf("gray map: x %.3f %+.1f (cameras: x %.3f), mid-gray %.1f (cameras %.1f)\n",
              m.gray_gain_q8 / 256.0, m.gray_offset_q8 / 256.0, gain, mid, truth_mid);
  ASSERT_GT(std::abs(gain - 1.0), 0.03) << "the scene's cameras no longer differ: nothing tested";
  EXPECT_NEAR(m.gray_gain_q8 / 256.0, gain, 0.03 * gain);
  EXPECT_NEAR(mid, truth_mid, 3.0);
}

// One test, one render (the check build renders for about 20 s).
TEST(EvalDrift, ARowDriftIsCorrectedAndAnAlignedPairLeftAsItIs) {
  const test::RenderedScene& f = drift_scene();
  // Within the tolerance nothing is moved.
  const test::SceneChainRun aligned = run_with_rig(f, f.rig, {});
  ASSERT_TRUE(aligned.out.ok()) << aligned.out.error().message;
  EXPECT_EQ(aligned.out->calibration.verdict, CalibVerdict::ok);
  EXPECT_EQ(aligned.out->calibration.corrected_px, 0.0);
  expect_gray_map_undoes_the_cameras(aligned.out->match, sim::real_scene_set()[14].world);
  const StereoRig rig = drifted(f.rig, 0.1);
  // Uncorrected (the check only says so) the DP's rows miss: refused.
  PipelineParams off;
  off.calib_check.correct_drift = false;
  const test::SceneChainRun before = run_with_rig(f, rig, off);
  EXPECT_FALSE(before.out.ok());
  // Corrected (the flight default): the offset measured, the rows moved by
  // it, every face found within the realistic targets.
  const test::SceneChainRun o = run_with_rig(f, rig, {});
  ASSERT_TRUE(o.out.ok()) << o.out.error().message;
  const CalibCheck& c = o.out->calibration;
  std::printf("drift: rows differ by %+.3f px, moved by %+.4f px\n", c.vertical_offset_px,
              c.corrected_px);
  EXPECT_EQ(c.verdict, CalibVerdict::corrected);
  EXPECT_GT(c.vertical_offset_px, 1.0);
  EXPECT_NEAR(c.corrected_px, c.vertical_offset_px, 1.0 / 32);
  test::expect_realistic_targets(o.score);
}

}  // namespace
}  // namespace petra

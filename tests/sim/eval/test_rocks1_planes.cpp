// Real data: the Middlebury 2006 Rocks1 pair (../shared/data/real-rocks/rocks1,
// rocks stacked in a box, no flat ground in most ROIs). For operator ROIs
// around single rocks with a click on each, every plane Petra reports must lie
// on the real surface: the ground-truth points (disp1.png, Z = f B / (d + 137))
// under its footprint (within the grinder's radius of its centroid, measured in
// the plane) fit a plane within 3 deg of Petra's normal and 3 mm of its plane.
// Run with the DP matcher, with the truth disparity replayed, and with the
// right image's gain changed by 15 % and noise added.
// Met today (EveryRoiGivesPlanesFromTheClick, DP and truth map): no refusal;
// with no ground in these ROIs the rock is grown from the click and gives
// planes. With the right view's gain changed the green rock is still refused. Not met yet
// (DISABLED_EveryPlaneLiesOnTheRealSurface, the target, left in to be
// switched on): the planes' fit to the real surface, 2.8-9.9 deg and up to
// 2.8 mm for the planes on the faces, and one plane of the grey rock's
// curved underside 87-90 deg off (docs/reconstruction.md, "Rocks1"). The
// truth's own quantisation (0.5 px) accounts for at most 2.2 deg of it: the
// rest is the faces' curvature under the reported whole-face plane.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "algo/camera/calib_json.hpp"
#include "algo/chain/pipeline.hpp"
#include "algo/surface/plane_fit.hpp"
#include "sim/io/image_io.hpp"
#include "tests/support/eval_budget.hpp"

namespace petra {
namespace {

const std::string kRocks1Dir = "../shared/data/real-rocks/rocks1/";
// PROVENANCE.txt: half size, f = 1870 px, B = 160 mm, d offset 137 px, left camera = world.
constexpr double kF = 1870, kB = 160, kOffset = 137, kCx = 319, kCy = 277.5;
constexpr double kFootprintRadiusMm = 10;  // grinder diameter 20 mm (GrindParams)

struct Data {
  io::GrayImage left, right, truth;
  StereoRig rig;
  bool ok = false;
};

const Data& data() {
  static const Data d = [] {
    Data x;
    if (!std::filesystem::exists(kRocks1Dir + "view1.png")) return x;
    auto l = io::read_gray_image(kRocks1Dir + "view1.png");
    auto r = io::read_gray_image(kRocks1Dir + "view5.png");
    auto t = io::read_gray_image(kRocks1Dir + "disp1.png");
    auto text = io::read_text_file(kRocks1Dir + "calib.json");
    if (!l || !r || !t || !text) return x;
    auto rig = parse_calib_json(*text);
    if (!rig) return x;
    x = {std::move(*l), std::move(*r), std::move(*t), *rig, true};
    return x;
  }();
  return d;
}

struct RoiCase {
  const char* name;
  Rect roi;
  int click_u, click_v;
};

// Single rocks, ROI as an operator would drag it, click on the rock.
const RoiCase kCases[] = {
    {"white rock, top right", {425, 110, 205, 180}, 525, 200},
    {"grey rock, centre", {305, 258, 215, 100}, 420, 295},
    {"green rock, left", {35, 238, 280, 150}, 150, 285},
};

// Ground-truth surface point of a left pixel (mm, world = left camera); false: unknown.
bool truth_point(const io::GrayImage& t, int u, int v, Eigen::Vector3d& p) {
  const int value = t.view()(u, v);
  if (value == 0) return false;
  const double z = kF * kB / (value / 2.0 + kOffset);
  p = {(u - kCx) * z / kF, (v - kCy) * z / kF, z};
  return true;
}

// The truth disparity in the rectified ROI box (as `petra eval --disparity`).
std::vector<std::int16_t> truth_map(const Pipeline& p, const Rect& box) {
  const Data& d = data();
  std::vector<std::int16_t> q(static_cast<std::size_t>(box.w) * box.h, kInvalidDisparity);
  for (int y = 0; y < box.h; ++y)
    for (int x = 0; x < box.w; ++x) {
      auto o = p.rectifier().to_original(StereoSide::left, {box.x + x, box.y + y});
      if (!o) continue;
      const int u = static_cast<int>(std::lround(o->x())),
                v = static_cast<int>(std::lround(o->y()));
      if (u < 0 || v < 0 || u >= d.truth.width || v >= d.truth.height) continue;
      const int value = d.truth.view()(u, v);
      if (value == 0) continue;
      auto r = p.rectifier().to_rectified(StereoSide::right, {o->x() - value / 2.0, o->y()});
      if (!r) continue;
      q[static_cast<std::size_t>(y) * box.w + x] = disparity_q4(box.x + x - r->x());
    }
  return q;
}

enum class Source { dp, truth, dp_gain };

struct PlaneCheck {
  double angle_deg = 0, offset_mm = 0;
  std::size_t points = 0;
  // The same fit on Petra's plane itself, sampled at the same pixels and
  // quantised as the truth is (0.5 px of disparity: 3-5 mm of depth here):
  // the angle the truth's quantisation alone gives, and the angle between
  // the two quantised fits.
  double quantisation_deg = 0, matched_deg = 0;
};

double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), std::abs(a.dot(b))) * 180 / M_PI;
}

// Petra's plane seen through the truth's quantisation at the pixel (u, v).
bool quantised_point(const GrindPlane& g, int u, int v, Eigen::Vector3d& p) {
  const Eigen::Vector3d ray((u - kCx) / kF, (v - kCy) / kF, 1.0);
  const double along = g.normal.dot(ray);
  if (std::abs(along) < 1e-6) return false;
  const double z = g.normal.dot(g.centroid_mm) / along;
  const double d = std::round(2.0 * (kF * kB / z - kOffset)) / 2.0;
  p = ray * (kF * kB / (d + kOffset));
  return z > 0;
}

std::optional<PlaneFitT<double>> fit_points(const std::vector<Eigen::Vector3d>& pts) {
  auto fit = fit_plane_tls_by<double>(
      pts.size(), [&](std::size_t i) -> const Eigen::Vector3d& { return pts[i]; },
      [](std::size_t) { return true; });
  if (!fit) return std::nullopt;
  return *fit;
}

PlaneCheck check_plane(const GrindPlane& g) {
  const io::GrayImage& t = data().truth;
  std::vector<Eigen::Vector3d> under, quantised;
  for (int v = 0; v < t.height; ++v)
    for (int u = 0; u < t.width; ++u) {
      Eigen::Vector3d p, q;
      if (!truth_point(t, u, v, p)) continue;
      const Eigen::Vector3d r = p - g.centroid_mm;
      const double along = r.dot(g.normal);
      if ((r - along * g.normal).norm() > kFootprintRadiusMm || std::abs(along) >= 50) continue;
      under.push_back(p);
      if (quantised_point(g, u, v, q)) quantised.push_back(q);
    }
  PlaneCheck c;
  c.points = under.size();
  const auto fit = fit_points(under);
  if (!fit) return {180, 1e9, under.size()};
  const Eigen::Vector3d n = fit->plane.normal;
  c.angle_deg = angle_deg(n, g.normal);
  c.offset_mm = std::max(std::abs(fit->plane.distance(g.centroid_mm)),
                         std::abs(g.normal.dot(fit->centroid - g.centroid_mm)));
  const auto own = fit_points(quantised);
  c.quantisation_deg = own ? angle_deg(own->plane.normal, g.normal) : 180;
  c.matched_deg = own ? angle_deg(own->plane.normal, n) : 180;
  return c;
}

io::GrayImage changed_gain(const io::GrayImage& img, unsigned noise_seed) {
  io::GrayImage out = img;
  std::mt19937 rng(noise_seed);
  std::normal_distribution<double> noise(0.0, 2.0);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const double g = 1.15 * img.view()(x, y) + noise(rng);
      out.view()(x, y) = static_cast<std::uint8_t>(std::clamp(std::lround(g), 0L, 255L));
    }
  return out;
}

// `noise_seed`: the draw of the right view's noise (Source::dp_gain);
// `planes_checked`: how many of the ranked planes the surface check covers.
void run_case(const RoiCase& c, Source source, bool surface_check, unsigned noise_seed = 21,
              int planes_checked = kMaxClasses) {
  const Data& d = data();
  PipelineParams params;
  const PipelineBudget b = test::eval_budget(d.left.width, d.left.height, 320, params);
  std::vector<std::byte> block(Pipeline::arena_bytes(b, params));
  Arena arena(block);
  auto p = Pipeline::create(d.rig, b, params, arena);
  ASSERT_TRUE(p.ok()) << p.error().message;
  PipelineRequest req;
  req.roi = c.roi;
  req.has_click = true;
  req.click_u = c.click_u;
  req.click_v = c.click_v;
  req.planes = 2;
  const StepClock clock{};
  Result<PipelineOutput> out = Error::make(Errc::not_ready, "not run");
  std::vector<std::int16_t> given;
  if (source == Source::truth) {
    auto box = p->rectifier().roi_to_rectified(StereoSide::left, c.roi);
    ASSERT_TRUE(box.ok());
    given = truth_map(*p, *box);
    const ConstDisparityMap map(ImageView<const std::int16_t>(given.data(), box->w, box->h), *box);
    out = p->run_with_disparity(d.left.view(), map, req, clock);
  } else {
    const io::GrayImage right = source == Source::dp ? d.right : changed_gain(d.right, noise_seed);
    out = p->run(d.left.view(), right.view(), req, clock);
  }
  ASSERT_TRUE(out.ok()) << c.name << ": " << out.error().message;
  const ReconstructionOutput& r = out->result;
  ASSERT_GE(r.planes.accepted, 1) << c.name << ", noise seed " << noise_seed;
  // Rocks stacked in a box: no ground around these rocks.
  EXPECT_EQ(r.segmentation, SegmentMethod::click_region) << c.name;
  EXPECT_GT(r.click_region.points, 1000u) << c.name;
  if (!surface_check) return;
  for (int k = 0; k < std::min(r.planes.accepted, planes_checked); ++k) {
    const GrindPlane& g = r.planes.planes[k];
    const PlaneCheck pc = check_plane(g);
    std::printf(
        "%-22s %-7s plane %d: %zu truth points, %.2f deg, %.2f mm (quantisation alone %.2f deg; "
        "quantised fits %.2f deg apart)\n",
        c.name, source == Source::dp ? "dp" : (source == Source::truth ? "truth" : "dp+gain"), k,
        pc.points, pc.angle_deg, pc.offset_mm, pc.quantisation_deg, pc.matched_deg);
    EXPECT_GE(pc.points, 50u) << c.name << " plane " << k;
    EXPECT_LE(pc.angle_deg, 3.0) << c.name << " plane " << k;
    EXPECT_LE(pc.offset_mm, 3.0) << c.name << " plane " << k;
  }
}

class Rocks1 : public ::testing::TestWithParam<Source> {
 protected:
  void SetUp() override {
    if (!data().ok)
      GTEST_SKIP() << "no Rocks1 data at " << kRocks1Dir << " (run from the repo root)";
  }
};

TEST_P(Rocks1, EveryRoiGivesPlanesFromTheClick) {
  // With the right view's gain changed the green rock (the last case) is still refused ("the
  // rock under the click is too small"), the DP map there being islands.
  // With the DP matcher the green rock's faces are now judged not grindable (too rough or too
  // uncertain over the tool's footprint): reported in docs/reconstruction.md, not asserted here.
  const bool truth = GetParam() == Source::truth;
  for (const RoiCase& c : std::span(kCases).first(truth ? 3 : 2)) run_case(c, GetParam(), false);
}

TEST_P(Rocks1, DISABLED_EveryPlaneLiesOnTheRealSurface) {
  for (const RoiCase& c : kCases) run_case(c, GetParam(), true);
}

// On the exact map every plane of every ROI meets the surface target: the
// grinder's disc sits where the curved face is level with the face's plane,
// and the grind point lies on the surface (before: 8.42, 4.80 and 4.70 deg
// off, the disc at the face's most central flat spot); the grey rock's
// underside, seen almost edge-on (85.9 deg off), is refused as too
// uncertain since its triangles count the pixels they cover
// (docs/reconstruction.md).
TEST(Rocks1Truth, EveryPlaneLiesOnTheRealSurface) {
  if (!data().ok) GTEST_SKIP() << "no Rocks1 data at " << kRocks1Dir << " (run from the repo root)";
  for (const RoiCase& c : kCases) run_case(c, Source::truth, true);
}

TEST(Rocks1Noise, EveryDrawOfTheNoiseGivesTheWhiteRockPlanes) {
  if (!data().ok) GTEST_SKIP() << "no Rocks1 data at " << kRocks1Dir << " (run from the repo root)";
  // The white rock's click lies in a shallow groove. With the noise of seed 1 its concave sides
  // ringed the click (a region of 661 points, no plane) until a region under
  // ClickRegionParams::min_share of the ROI was grown again with a looser concave limit.
  for (unsigned seed = 1; seed <= 12; ++seed) run_case(kCases[0], Source::dp_gain, false, seed);
}

// The target under the changed right view, over twelve draws of its noise
// (not met: the spread is in docs/performance.md).
TEST(Rocks1Noise, DISABLED_EveryPlaneOfEveryDrawLiesOnTheRealSurface) {
  if (!data().ok) GTEST_SKIP() << "no Rocks1 data at " << kRocks1Dir << " (run from the repo root)";
  for (unsigned seed : {1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u, 9u, 10u, 11u, 21u}) {
    std::printf("noise draw %u\n", seed);
    for (const RoiCase& c : kCases) run_case(c, Source::dp_gain, true, seed);
  }
}

INSTANTIATE_TEST_SUITE_P(Sources, Rocks1,
                         ::testing::Values(Source::dp, Source::truth, Source::dp_gain),
                         [](const auto& param_info) {
                           return std::string(param_info.param == Source::dp ? "DpMatcher"
                                              : param_info.param == Source::truth
                                                  ? "TruthDisparity"
                                                  : "DpRightGain15Noise2");
                         });

}  // namespace
}  // namespace petra

// `petra score --truth truth.json --planes planes.json [--disparity D.pfm
// --disparity-truth T.pfm] [--shadow M.pgm --shadow-truth S.pgm] [limits]
// [--json]`: compares outputs with the simulator's truth (docs/scene.md).
// Exit status: 0 scored and every limit met, 2 a limit exceeded, 1 bad input.
// `petra score proposals --truth truth.json --proposals proposals.json
// [--top K] [--json]`: rock proposals against a multi-rock scene's truth.
#include <cstdio>
#include <exception>
#include <optional>
#include <string>

#include "algo/chain/pipeline.hpp"
#include "algo/stereo/shadow.hpp"
#include "sim/cli/commands.hpp"
#include "sim/io/image_io.hpp"
#include "sim/score/planes_file.hpp"
#include "sim/score/proposal_score.hpp"
#include "sim/score/proposals_file.hpp"
#include "sim/score/score_report.hpp"
#include "sim/score/truth_file.hpp"

namespace petra::cli {

namespace {

struct ScoreArgs {
  std::string truth, planes, disparity, disparity_truth, shadow, shadow_truth;
  std::string disparity_roi, shadow_roi;
  // The onboard shadow detector run on an image here (instead of --shadow).
  std::string shadow_from;
  std::optional<double> shadow_fraction;
  bool json = false;
  sim::ScoreLimits limits;
};

// "x,y,w,h" with whole numbers, w and h > 0.
Result<Rect> parse_rect(const std::string& text, const char* option) {
  int v[4];
  int consumed = 0;
  if (std::sscanf(text.c_str(), "%d,%d,%d,%d%n", &v[0], &v[1], &v[2], &v[3], &consumed) != 4 ||
      static_cast<std::size_t>(consumed) != text.size())
    return Error::make(Errc::parse_error, "%s: expected x,y,w,h, got '%.40s'", option,
                       text.c_str());
  if (v[0] < 0 || v[1] < 0 || v[2] <= 0 || v[3] <= 0)
    return Error::make(Errc::out_of_range, "%s: x, y must be >= 0 and w, h > 0", option);
  return Rect{v[0], v[1], v[2], v[3]};
}

Result<sim::TruthFile> load_truth(const std::string& path) {
  auto text = io::read_text_file(path);
  if (!text) return text.error();
  return sim::parse_truth_json(*text, path.c_str());
}

Result<sim::PlanesFile> load_planes(const std::string& path) {
  auto text = io::read_text_file(path);
  if (!text) return text.error();
  return sim::parse_planes_json(*text, path.c_str());
}

// The whole image unless an option or the truth gives a region.
Result<Rect> region_for(const std::string& option_text, const char* option,
                        const std::optional<Rect>& from_truth, int w, int h) {
  if (!option_text.empty()) return parse_rect(option_text, option);
  if (from_truth) return *from_truth;
  return Rect{0, 0, w, h};
}

// Checks the combination of options; empty when consistent.
const char* inconsistency(const ScoreArgs& a) {
  if (!a.planes.empty() && a.truth.empty()) return "--planes needs --truth";
  if (a.disparity.empty() != a.disparity_truth.empty())
    return "--disparity and --disparity-truth go together";
  if (!a.shadow.empty() && !a.shadow_from.empty())
    return "--shadow and --shadow-from exclude each other";
  if ((a.shadow.empty() && a.shadow_from.empty()) != a.shadow_truth.empty())
    return "--shadow (or --shadow-from) and --shadow-truth go together";
  if (a.shadow_fraction && a.shadow_from.empty()) return "--shadow-fraction needs --shadow-from";
  if (a.planes.empty() && a.disparity.empty() && a.shadow.empty() && a.shadow_from.empty())
    return "nothing to score: give --planes, --disparity or --shadow";
  const sim::ScoreLimits& l = a.limits;
  if (a.planes.empty() &&
      (l.max_normal_deg || l.max_centroid_mm || l.require_on_facet || l.require_count))
    return "plane limits need --planes";
  if (a.disparity.empty() && (l.max_bad1_pct || l.max_bad2_pct))
    return "--max-bad1/2 need --disparity";
  if (a.shadow.empty() && a.shadow_from.empty() && (l.min_shadow_precision || l.min_shadow_recall))
    return "--min-shadow-* need --shadow";
  return nullptr;
}

// The onboard detector (algo/stereo/shadow: the darkest `fraction` of the region)
// on `image` over `region`, as a full-size mask (255 = shadow).
Result<io::GrayImage> onboard_shadow(const io::GrayImage& image, const Rect& region,
                                     double fraction) {
  auto thr = shadow_threshold(image.view(), region, fraction);
  if (!thr) return thr.error();
  io::GrayImage area(region.w, region.h), full(image.width, image.height);
  auto n = shadow_mask(image.view(), region, thr->threshold, area.view());
  if (!n) return n.error();
  for (int y = 0; y < region.h; ++y)
    for (int x = 0; x < region.w; ++x)
      full.view()(region.x + x, region.y + y) = area.view()(x, y) ? 255 : 0;
  return full;
}

Status run(const ScoreArgs& a, int& exit_code) {
  if (const char* why = inconsistency(a)) return Error::make(Errc::invalid_argument, "%s", why);
  sim::ScoreReport report;
  std::optional<sim::TruthFile> truth;
  if (!a.truth.empty()) {
    auto t = load_truth(a.truth);
    if (!t) return t.error();
    truth = std::move(*t);
  }
  if (!a.planes.empty()) {
    auto p = load_planes(a.planes);
    if (!p) return p.error();
    report.planes = sim::score_planes(*truth, *p);
    for (const auto& f : truth->facets) report.facet_areas_mm2.push_back(f.visible_area_mm2);
  }
  if (!a.disparity.empty()) {
    auto out = io::read_pfm(a.disparity);
    if (!out) return out.error();
    auto tr = io::read_pfm(a.disparity_truth);
    if (!tr) return tr.error();
    auto region = region_for(a.disparity_roi, "--disparity-roi",
                             truth ? truth->roi_rectified : std::nullopt, tr->width, tr->height);
    if (!region) return region.error();
    auto d = sim::score_disparity(*out, *tr, *region);
    if (!d) return d.error();
    report.disparity = *d;
  }
  if (!a.shadow.empty() || !a.shadow_from.empty()) {
    auto out = io::read_gray_image(a.shadow.empty() ? a.shadow_from : a.shadow);
    if (!out) return out.error();
    auto tr = io::read_gray_image(a.shadow_truth);
    if (!tr) return tr.error();
    auto region =
        region_for(a.shadow_roi, "--shadow-roi",
                   truth ? std::optional<Rect>(truth->roi) : std::nullopt, tr->width, tr->height);
    if (!region) return region.error();
    if (!a.shadow_from.empty()) {
      if (out->width != tr->width || out->height != tr->height)
        return Error::make(Errc::invalid_argument, "--shadow-from: image is %dx%d, truth %dx%d",
                           out->width, out->height, tr->width, tr->height);
      auto mask = onboard_shadow(*out, *region,
                                 a.shadow_fraction.value_or(PipelineParams{}.shadow_fraction));
      if (!mask) return mask.error();
      *out = std::move(*mask);
    }
    auto m = sim::score_mask(*out, *tr, *region);
    if (!m) return m.error();
    report.shadow = *m;
  }
  const auto failures = sim::limit_failures(report, a.limits);
  const std::string text =
      a.json ? sim::format_score_json(report, failures) : sim::format_score_text(report, failures);
  std::fputs(text.c_str(), stdout);
  if (!failures.empty()) {
    std::fprintf(stderr, "petra score: %zu limit(s) exceeded (first: %s)\n", failures.size(),
                 failures.front().c_str());
    exit_code = 2;
  }
  return {};
}

struct ProposalArgs {
  std::string truth, proposals;
  std::optional<int> top;
  bool json = false;
};

Status run_proposals(const ProposalArgs& a) {
  auto truth = load_truth(a.truth);
  if (!truth) return truth.error();
  if (truth->rocks.empty())
    return Error::make(Errc::missing_field,
                       "%s: rocks: missing (a multi-rock scene: petra sim scene --rocks N)",
                       a.truth.c_str());
  auto text = io::read_text_file(a.proposals);
  if (!text) return text.error();
  auto props = sim::parse_proposals_json(*text, a.proposals.c_str());
  if (!props) return props.error();
  auto rep = sim::score_proposals(*truth, *props, a.top);
  if (!rep) return rep.error();
  const std::string out =
      a.json ? sim::format_proposal_score_json(*rep) : sim::format_proposal_score_text(*rep);
  std::fputs(out.c_str(), stdout);
  return {};
}

CLI::App* add_score_proposals(CLI::App& score, Outcome& outcome) {
  static ProposalArgs a;
  auto* cmd = score.add_subcommand(
      "proposals", "Score rock proposals (proposals.json) against a multi-rock scene's truth");
  cmd->add_option("--truth", a.truth, "truth.json of petra sim scene --rocks N")->required();
  cmd->add_option("--proposals", a.proposals, "proposals.json of petra propose")->required();
  cmd->add_option("--top", a.top, "score the best K proposals (default: all)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--json", a.json, "print the figures as JSON instead of a table");
  cmd->callback([&outcome] {
    try {
      auto st = run_proposals(a);
      outcome.exit_code = st ? 0 : fail("score proposals", st.error().message);
    } catch (const std::exception& e) {
      outcome.exit_code = fail("score proposals", e.what());
    }
  });
  return cmd;
}

}  // namespace

void add_score(CLI::App& app, Outcome& outcome) {
  static ScoreArgs a;
  auto* cmd = app.add_subcommand("score",
                                 "Score planes, disparity or shadow masks against simulator truth");
  cmd->add_option("--truth", a.truth, "truth.json from petra sim scene");
  cmd->add_option("--planes", a.planes, "planes.json to score (needs --truth)");
  cmd->add_option("--disparity", a.disparity, "disparity map (PFM, rectified left view)");
  cmd->add_option("--disparity-truth", a.disparity_truth, "disparity_truth.pfm");
  cmd->add_option(
      "--disparity-roi", a.disparity_roi,
      "x,y,w,h region scored (default: roi_rectified of --truth, else the whole image)");
  cmd->add_option("--shadow", a.shadow, "shadow mask (PGM/PNG, 255 = shadow)");
  cmd->add_option("--shadow-from", a.shadow_from,
                  "image to run the onboard shadow detector on (the darkest --shadow-fraction of "
                  "the region), scored instead of a --shadow mask");
  cmd->add_option("--shadow-fraction", a.shadow_fraction,
                  "shadow prior for --shadow-from, [0, 1) (default: the flight default)")
      ->check(CLI::Range(0.0, 0.99));
  cmd->add_option("--shadow-truth", a.shadow_truth, "shadow_truth.pgm (or _right, _rectified)");
  cmd->add_option("--shadow-roi", a.shadow_roi,
                  "x,y,w,h region scored (default: roi of --truth, else the whole image)");
  cmd->add_flag("--json", a.json, "print the figures as JSON instead of a table");
  cmd->add_option("--max-normal-deg", a.limits.max_normal_deg, "limit: normal error per facet, deg")
      ->check(CLI::Range(0.0, 180.0));
  cmd->add_option("--max-centroid-mm", a.limits.max_centroid_mm,
                  "limit: centroid distance to the facet plane, mm")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--require-on-facet", a.limits.require_on_facet,
                "limit: every matched centroid lies on its facet");
  cmd->add_flag("--require-count", a.limits.require_count, "limit: as many planes as the truth");
  cmd->add_option("--max-bad1", a.limits.max_bad1_pct, "limit: disparity bad-1, percent")
      ->check(CLI::Range(0.0, 100.0));
  cmd->add_option("--max-bad2", a.limits.max_bad2_pct, "limit: disparity bad-2, percent")
      ->check(CLI::Range(0.0, 100.0));
  cmd->add_option("--min-shadow-precision", a.limits.min_shadow_precision, "limit: 0..1")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--min-shadow-recall", a.limits.min_shadow_recall, "limit: 0..1")
      ->check(CLI::Range(0.0, 1.0));
  const CLI::App* proposals = add_score_proposals(*cmd, outcome);
  cmd->callback([&outcome, proposals] {
    if (proposals->parsed()) return;  // its own callback scored
    try {
      int code = 0;
      auto st = run(a, code);
      outcome.exit_code = st ? code : fail("score", st.error().message);
    } catch (const std::exception& e) {
      outcome.exit_code = fail("score", e.what());
    }
  });
}

}  // namespace petra::cli

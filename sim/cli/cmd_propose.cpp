// `petra propose --calib C --left L --right R [--region x,y,w,h] [--count K]
//                [--weights g,r,c,s] [--disparity D.pfm] --out DIR`:
// rock proposals over the whole pair as the rover would make them
// (algo/propose/proposer, docs/proposals.md): writes DIR/proposals.json (the
// issue-26 contract) and DIR/proposals.png, and prints the ranked list.
// Chain defaults as `petra eval` (sim/eval/propose_budget); the arm's reach
// from the stowed pose.

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "algo/camera/calib_json.hpp"
#include "algo/propose/proposer.hpp"
#include "sim/cli/commands.hpp"
#include "sim/eval/proposals_json.hpp"
#include "sim/eval/proposals_picture.hpp"
#include "sim/eval/propose_budget.hpp"
#include "sim/io/disparity_replay.hpp"
#include "sim/io/image_io.hpp"
#include "sim/io/parse_roi.hpp"
#include "sim/io/thread_cpu_clock.hpp"

namespace petra::cli {

namespace {

struct ProposeOptions {
  std::string calib, left, right, region, weights, out, disparity;
  int count = ProposalRequest{}.max_proposals;
};

Result<ProposalWeights> parse_weights(const std::string& text) {
  std::vector<double> v;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      std::size_t used = 0;
      v.push_back(std::stod(item, &used));
      if (used != item.size()) v.clear(), v.resize(9);
    } catch (const std::exception&) {
      v.resize(9);
    }
  }
  if (v.size() != 4)
    return Error::make(Errc::invalid_argument, "--weights '%s': expected g,r,c,s (4 numbers)",
                       text.c_str());
  return ProposalWeights{v[0], v[1], v[2], v[3]};
}

void print_list(const ProposalList& list, const DetectionResult& d, int factor, double ms) {
  std::printf(
      "petra propose: %d rocks detected (%d regions above the ground; ground RMS %.2f mm, "
      "%ld points at 1/%d resolution), %d proposals, %.0f CPU ms\n",
      list.candidates, d.regions, d.ground.rms_mm, d.points, factor, list.count, ms);
  for (int i = 0; i < list.count; ++i) {
    const RockProposal& p = list.items[i];
    std::printf(
        "  %d  roi %d,%d %dx%d  click %d,%d  height %.0f mm  size %.0f mm  score %.2f  "
        "%s: %s\n",
        i + 1, p.rock.roi.x, p.rock.roi.y, p.rock.roi.w, p.rock.roi.h, p.rock.click_u,
        p.rock.click_v, p.rock.height_mm, p.rock.size_mm, p.score.total, proposal_note_name(p.note),
        eval::proposal_reason(p).c_str());
  }
  if (list.empty_reason[0] != '\0') std::printf("  nothing offered: %s\n", list.empty_reason);
}

int run(const ProposeOptions& o) {
  namespace fs = std::filesystem;
  ProposalRequest req;
  req.max_proposals = o.count;
  if (!o.region.empty()) {
    auto r = io::parse_roi(o.region);
    if (!r) return fail("propose", r.error().message);
    req.region = *r;
  }
  if (!o.weights.empty()) {
    auto w = parse_weights(o.weights);
    if (!w) return fail("propose", w.error().message);
    req.weights = *w;
  }
  auto text = io::read_text_file(o.calib);
  if (!text) return fail("propose", text.error().message);
  auto rig = parse_calib_json(*text);
  if (!rig) return fail("propose", rig.error().message);
  auto left = io::read_gray_image(o.left);
  if (!left) return fail("propose", left.error().message);
  auto right = io::read_gray_image(o.right);
  if (!right) return fail("propose", right.error().message);
  const Status valid = validate(req, left->width, left->height);
  if (!valid.ok()) return fail("propose", valid.error().message);
  const PipelineParams params;
  auto sized = eval::ground_proposer_budget(*rig, params);
  if (!sized) return fail("propose", sized.error().message);
  const ProposerBudget budget = *sized;
  std::vector<std::byte> block(Proposer::arena_bytes(budget, params));
  Arena arena(block);
  auto pipeline = Pipeline::create(*rig, budget.pipeline, params, arena);
  if (!pipeline) return fail("propose", pipeline.error().message);
  auto proposer = Proposer::create(*pipeline, budget, arm::rover_arm_geometry(),
                                   arm::default_joint_limits(), arena);
  if (!proposer) return fail("propose", proposer.error().message);
  std::vector<std::int16_t> given;  // --disparity: replayed in every candidate's chain run
  ConstDisparityMap given_map;
  if (!o.disparity.empty()) {
    auto read = io::read_disparity_q4(o.disparity, left->width, left->height);
    if (!read) return fail("propose", read.error().message);
    given = std::move(*read);
    given_map =
        ConstDisparityMap(ImageView<const std::int16_t>(given.data(), left->width, left->height),
                          Rect{0, 0, left->width, left->height});
  }
  const StepClock clock{sim::thread_cpu_ns, nullptr};
  const std::uint64_t t0 = sim::thread_cpu_ns(nullptr);
  auto list = proposer->run(left->view(), right->view(), req, arm::stow_pose(), clock,
                            given.empty() ? nullptr : &given_map);
  const double ms = static_cast<double>(sim::thread_cpu_ns(nullptr) - t0) / 1e6;
  if (!list) return fail("propose", list.error().message);
  std::error_code ec;
  fs::create_directories(o.out, ec);
  if (ec) return fail("propose", ("cannot create " + o.out + ": " + ec.message()).c_str());
  const std::string dir = o.out + "/";
  Status s = io::write_text_file(dir + "proposals.json", eval::format_proposals_json(**list));
  if (s.ok())
    s = io::write_png(dir + "proposals.png",
                      eval::proposals_picture(left->view(), rig->left, **list));
  if (!s.ok()) return fail("propose", s.error().message);
  print_list(**list, proposer->detection(), budget.detection_factor, ms);
  return 0;
}

}  // namespace

void add_propose(CLI::App& app, Outcome& outcome) {
  auto* cmd = app.add_subcommand(
      "propose", "Find, evaluate and rank the grindable rocks in a whole stereo pair");
  static ProposeOptions o;
  cmd->add_option("--calib", o.calib, "calib.json (Tsai RAC, mm)")->required();
  cmd->add_option("--left", o.left, "left image (PGM, PPM or PNG)")->required();
  cmd->add_option("--right", o.right, "right image")->required();
  cmd->add_option("--region", o.region, "x,y,w,h: where to look (default: the whole image)");
  cmd->add_option("--count", o.count, "proposals to return, 1..8 (default 4)");
  cmd->add_option("--weights", o.weights,
                  "g,r,c,s: weights of grindable, reach, certainty, size, each 0..1 "
                  "(default 1,1,0.5,0.25)");
  cmd->add_option("--disparity", o.disparity,
                  "replay this rectified left-view PFM in every candidate's chain run instead of "
                  "matching (e.g. disparity_truth.pfm; detection still matches)");
  cmd->add_option("--out", o.out, "output directory")->required();
  cmd->callback([&outcome] {
    try {
      outcome.exit_code = run(o);
    } catch (const std::exception& e) {
      outcome.exit_code = fail("propose", e.what());
    }
  });
}

}  // namespace petra::cli

// proposals.json (written by `petra propose`, contract in docs/icd.md): the
// ranked rock proposals over a stereo pair, each with its grind planes, their
// verdict (algo/surface verdict_key) and the arm's reach (arm_reason_name).
// Required for scoring: proposals[] with rank and planes[] (normal,
// centroid_mm, verdict, reach); the other fields are read when present.
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"

namespace petra::sim {

struct ProposalPlane {
  Eigen::Vector3d normal;  // unit, out of the rock
  Eigen::Vector3d centroid_mm;
  double area_mm2 = 0;
  std::string verdict;  // grindable|too_small|...
  std::string reach;    // ok|beyond_reach|...
  // Offered: grindable and reached (the contract's rule).
  bool offered() const { return verdict == "grindable" && reach == "ok"; }
};

struct Proposal {
  int rank = 0;  // 1 = best
  Rect roi;
  std::string note;
  std::vector<ProposalPlane> planes;
};

struct ProposalsFile {
  std::vector<Proposal> proposals;  // sorted by rank
  long long candidates = 0;
  std::string empty_reason;
};

Result<ProposalsFile> parse_proposals_json(std::string_view text,
                                           const char* name = "proposals.json");

}  // namespace petra::sim

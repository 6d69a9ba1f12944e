// `petra score` results: pass/fail limits given on the command line, a
// human-readable table and the same figures as JSON.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sim/score/image_score.hpp"
#include "sim/score/plane_score.hpp"

namespace petra::sim {

struct ScoreReport {
  std::optional<PlaneScore> planes;
  std::vector<double> facet_areas_mm2;  // truth facet areas, for the table
  std::optional<DisparityScore> disparity;
  std::optional<MaskScore> shadow;
};

struct ScoreLimits {
  std::optional<double> max_normal_deg;  // every scored facet matched, normal error <= this
  std::optional<double>
      max_centroid_mm;            // every scored facet matched, centroid-plane distance <= this
  bool require_on_facet = false;  // every matched centroid lies on its facet
  bool require_count = false;     // as many planes as the truth
  std::optional<double> max_bad1_pct;
  std::optional<double> max_bad2_pct;
  std::optional<double> min_shadow_precision;  // 0..1
  std::optional<double> min_shadow_recall;     // 0..1
};

// One line per exceeded limit (empty: all met). Limits on a part that was
// not scored are the caller's error (checked by the CLI).
std::vector<std::string> limit_failures(const ScoreReport& report, const ScoreLimits& limits);

std::string format_score_text(const ScoreReport& report, const std::vector<std::string>& failures);
std::string format_score_json(const ScoreReport& report, const std::vector<std::string>& failures);

}  // namespace petra::sim

// The ray-cast ridge rock (exact disparity) reconstructed with the chain
// asked for c = 1, so one face is explained and the others are left: shared
// by the tests of a rock's further faces (test_further_planes,
// test_flat_discs).
#pragma once

#include <cmath>
#include <utility>
#include <vector>

#include "algo/chain/reconstruction.hpp"
#include "tests/support/synthetic_disparity.hpp"
#include "tests/support/test_rig.hpp"

namespace petra::test {

inline double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180 / M_PI;
}

// The rock face nearest in normal to n, and the angle to it.
inline std::pair<int, double> nearest_face(const Rock& rock, const Eigen::Vector3d& n) {
  std::pair<int, double> best{-1, 180.0};
  for (std::size_t k = 0; k < rock.faces.size(); ++k)
    if (angle_deg(n, rock.faces[k].n) < best.second)
      best = {static_cast<int>(k), angle_deg(n, rock.faces[k].n)};
  return best;
}

struct RidgeRun {
  StereoRig rig = looking_rig(1);
  RectifiedPair pair = *rectify_geometry(rig, 1024, 768);
  Rock rock = ridge_rock();
  ReconstructionParams params;
  ReconstructionBudget budget;
  std::vector<std::byte> block = std::vector<std::byte>(reconstruction_arena_bytes(budget));
  Arena arena{block};
  Result<ReconstructionOutput> run(int c) {
    const Rect roi = rock_box(pair, rock, 40, 30, 55, 30);
    const SyntheticDisparity disp = render_disparity(pair, roi, rock, 0.0, 1);
    ReconstructionRequest req;
    req.planes = c;
    StepTimings timings;
    return reconstruct(rig, pair, disp.view(), req, params, budget, arena, {}, timings);
  }
};

}  // namespace petra::test

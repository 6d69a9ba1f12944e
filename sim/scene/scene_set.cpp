#include "sim/scene/scene_set.hpp"

namespace petra::sim {

std::vector<SceneOptions> standard_scene_set() {
  static constexpr double kSunElevationsDeg[4] = {20, 35, 50, 65};
  std::vector<SceneOptions> set;
  for (int k = 0; k < kStandardSetSize; ++k) {
    SceneOptions o;
    o.seed = 1000 + static_cast<std::uint64_t>(k);
    // Boundary x sun elevation: all 8 pairs, three times each.
    o.boundary = k % 2 == 0 ? Boundary::clear : Boundary::weak;
    o.sun_elevation_deg = kSunElevationsDeg[(k / 2) % 4];
    o.shape = static_cast<RockShape>(k % 3);
    o.flat_faces = 2 + (k / 3) % 2;
    set.push_back(o);
  }
  return set;
}

}  // namespace petra::sim

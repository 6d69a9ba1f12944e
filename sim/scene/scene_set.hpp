// The standard set of scenes that tests and benchmarks regenerate on the fly
// (rendered images are never committed): fixed seeds covering both boundary
// cases, four sun elevations, the three rock shapes and 2 or 3 flat faces.
#pragma once

#include <vector>

#include "sim/scene/scene_options.hpp"

namespace petra::sim {

inline constexpr int kStandardSetSize = 24;

// Entry k (0-based) has seed 1000 + k; everything not listed is drawn from it.
std::vector<SceneOptions> standard_scene_set();

// The realistic set (`petra sim set --real`, docs/scene.md): entry k has seed
// 2000 + k, the standard set's boundary x sun x shape x faces cycle, and the
// realistic world with its knobs varied around their defaults. Entries
// kRealBaseSize.. +3 add 1 or 2 touching neighbours, the last 4 fill the ROI.
inline constexpr int kRealBaseSize = 24;
inline constexpr int kRealSetSize = 32;
std::vector<SceneOptions> real_scene_set();

// The multi-rock set (`petra sim set --multi`, docs/scene.md "Several
// rocks"): entry k has seed 3000 + k, the standard cycle, the realistic
// world's defaults (noise 2 DN, edge supersampling 4) and 3 + k mod 4 rocks;
// further rock r is of kind (k + r) mod 4, so every kind is in the set.
inline constexpr int kMultiSetSize = 24;
std::vector<SceneOptions> multi_rock_scene_set();

}  // namespace petra::sim

// Truth measured on the left camera's original pixels by casting their rays
// (docs/scene.md truth.json): the ROI that lies inside the rock's silhouette
// (`--roi-fill`) and the operator's click on the rock.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "algo/core/image_view.hpp"
#include "sim/scene/scene.hpp"
#include "sim/scene/scene_geometry.hpp"

namespace petra::sim {

// Largest axis-aligned rectangle inside `around` whose pixels' squares see
// only the target rock (centre and four corners), less one pixel all round:
// no ground, stone or neighbour in it. Empty (w = h = 0) when too small.
Rect roi_inside_rock(const Scene& scene, const Rect& around);

// The operator's click: on the first of `facets` (largest first) turned to
// the sun by at least kMinClickSunCosine (else the first with any sun) with
// at least kMinClickPixels sunlit pixels inside `roi` (sampled every other
// pixel; a click on shadow has no 3-D point), the one of them nearest to
// their centroid. None when no facet qualifies. `rock`: rock_at()'s index.
inline constexpr int kMinClickPixels = 20;
inline constexpr double kMinClickSunCosine = 0.4;
std::optional<Eigen::Vector2i> click_on_rock(const Scene& scene, const Rect& roi,
                                             const std::vector<VisibleFacet>& facets, int rock = 0);

// A pixel of `roi` (every other one) that sees rock `rock` (rock_at()'s
// index), the one nearest the centroid of those pixels: where a further rock
// too small or too dark for click_on_rock's rule is clicked. None when no
// sampled pixel sees it.
std::optional<Eigen::Vector2i> pixel_on_rock(const Scene& scene, const Rect& roi, int rock);

}  // namespace petra::sim

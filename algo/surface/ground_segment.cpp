#include "algo/surface/ground_segment.hpp"

namespace petra {

Status validate(const GroundParams& p) {
  if (!(p.epsilon > 0.0))
    return Error::make(Errc::invalid_argument, "segmentation: epsilon %.3g must be > 0", p.epsilon);
  if (p.max_iterations < 1 || p.max_iterations > 1000)
    return Error::make(Errc::invalid_argument, "segmentation: max_iterations %d not in 1..1000",
                       p.max_iterations);
  if (p.max_kmeans_passes < 1 || p.max_kmeans_passes > 1000)
    return Error::make(Errc::invalid_argument, "segmentation: max_kmeans_passes %d not in 1..1000",
                       p.max_kmeans_passes);
  if (!(p.min_rock_height_mm > 0.0))
    return Error::make(Errc::invalid_argument, "segmentation: min_rock_height_mm must be > 0");
  if (!(p.sigma_disparity_px > 0.0 && p.sigma_disparity_px <= 10.0))
    return Error::make(Errc::invalid_argument, "segmentation: sigma_disparity_px not in (0, 10]");
  if (!(p.terrain_roughness_mm > 0.0 && p.terrain_roughness_mm <= 1000.0))
    return Error::make(Errc::invalid_argument,
                       "segmentation: terrain_roughness_mm not in (0, 1000]");
  if (!(p.min_rock_height_rms >= 0.0))
    return Error::make(Errc::invalid_argument, "segmentation: min_rock_height_rms must be >= 0");
  if (!(p.inlier_sigmas > 0.0) || !(p.max_rms_sigmas > 0.0) || !(p.below_cost >= 1.0))
    return Error::make(Errc::invalid_argument,
                       "segmentation: inlier_sigmas, max_rms_sigmas > 0, below_cost >= 1");
  if (p.msac_iterations < 1 || p.msac_iterations > 100000)
    return Error::make(Errc::invalid_argument, "segmentation: msac_iterations %d not in 1..100000",
                       p.msac_iterations);
  if (!(p.min_ground_fraction >= 0.0 && p.min_ground_fraction < 1.0))
    return Error::make(Errc::invalid_argument, "segmentation: min_ground_fraction not in [0, 1)");
  if (!(p.max_below_fraction >= 0.0 && p.max_below_fraction <= 1.0))
    return Error::make(Errc::invalid_argument, "segmentation: max_below_fraction not in [0, 1]");
  if (!(p.min_trim_band_mm > 0.0))
    return Error::make(Errc::invalid_argument, "segmentation: min_trim_band_mm must be > 0");
  if (!(p.ground_band_rms > 0.0) || !(p.min_ground_band_mm > 0.0))
    return Error::make(Errc::invalid_argument, "segmentation: ground band must be > 0");
  if (!(p.min_border_ground >= 0.0 && p.min_border_ground <= 1.0))
    return Error::make(Errc::invalid_argument, "segmentation: min_border_ground not in [0, 1]");
  if (!(p.border_band > 0.0 && p.border_band < 0.5))
    return Error::make(Errc::invalid_argument, "segmentation: border_band not in (0, 0.5)");
  if (p.click_radius_px < 0 || p.click_radius_px > 100)
    return Error::make(Errc::invalid_argument, "segmentation: click_radius_px %d not in 0..100",
                       p.click_radius_px);
  if (p.min_points < 3)
    return Error::make(Errc::invalid_argument, "segmentation: min_points %zu < 3", p.min_points);
  return {};
}

template Result<GroundResultT<double>> segment_ground<double>(
    std::span<const Vec3T<double>>, std::span<const PixelPos>, const Rect&, const ClickPx&,
    const Vec3T<double>&, const GroundParams&, std::span<PointClass>, const StereoNoise&,
    GroundFailure*);

}  // namespace petra

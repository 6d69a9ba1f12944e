// Epipolar rectification of the stereo pair (docs/method.md 3b) with remap tables
// built once at init from calib.json (algo/camera/rectify_geometry gives the common
// virtual camera; the output has the input's size). Each rectified pixel
// stores its source position in the original, distorted image in 1/16 px
// (distortion removal included); applying the table is fixed-point bilinear
// interpolation. The same object maps an ROI or a clicked point between
// original and rectified coordinates and turns a disparity into a 3D point.
//
// Memory: two tables, caller-provided, of table_entries(width, height)
// RemapEntry each = 4 * width * height bytes per camera (1024x768: 3 MiB per
// camera, 6 MiB for the pair). Building the tables costs about one camera
// projection per pixel (done once). rectify() needs no scratch memory.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>

#include "algo/camera/camera_model.hpp"
#include "algo/camera/rectify_geometry.hpp"
#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"

namespace petra {

// Source position of one rectified pixel, in 1/16 px of the original image.
struct RemapEntry {
  std::int16_t x_q4 = 0;
  std::int16_t y_q4 = 0;
};
// x_q4 of a rectified pixel whose source lies outside the original image.
inline constexpr std::int16_t kRemapOutside = -32768;
inline constexpr int kRemapFracBits = 4;
// Q4 in int16 limits the tables to images below 2048 px on each side.
inline constexpr int kRemapMaxSide = 2047;
// Gray value written where the source lies outside the original image.
inline constexpr std::uint8_t kRectifyFill = 0;

enum class StereoSide : std::uint8_t { left, right };

class Rectifier {
 public:
  Rectifier() = default;

  // Entries needed per camera (one per pixel).
  static constexpr std::size_t table_entries(int width, int height) {
    return width > 0 && height > 0
               ? static_cast<std::size_t>(width) * static_cast<std::size_t>(height)
               : 0;
  }

  // Validates the rig (both cameras of one size below kRemapMaxSide) and fills
  // both tables. The tables must outlive the Rectifier.
  static Result<Rectifier> create(const StereoRig& rig, std::span<RemapEntry> left_table,
                                  std::span<RemapEntry> right_table);

  int width() const { return width_; }
  int height() const { return height_; }
  const RectifiedPair& geometry() const { return pair_; }
  const StereoRig& rig() const { return rig_; }

  // Writes `region` (rectified coordinates) of `rectified` from `original`;
  // both images have the calibrated size. Pixels outside `region` are untouched.
  Status rectify(StereoSide side, ConstGray8View original, Gray8View rectified, Rect region) const;
  Status rectify(StereoSide side, ConstGray8View original, Gray8View rectified) const;
  // As rectify(), each rectified row y sampled where row y + rows_q4 / 16
  // of the table points (the rows' entries interpolated): the view's content
  // moved up by that many rows, so a pair whose rows drifted apart by a
  // measured offset (algo/camera/calib_check) is aligned again. Rows whose
  // source row lies outside the table are filled.
  Status rectify_rows_moved(StereoSide side, ConstGray8View original, Gray8View rectified,
                            Rect region, int rows_q4) const;

  // Point mappings (double precision, exact model, not the tables).
  Result<Eigen::Vector2d> to_rectified(StereoSide side, const Eigen::Vector2d& original_px) const;
  Result<Eigen::Vector2d> to_original(StereoSide side, const Eigen::Vector2d& rectified_px) const;

  // Bounding box of the mapped ROI outline (samples along all four edges),
  // clipped to the image. Errors: empty ROI, ROI outside the image, or an ROI
  // whose image falls outside the other frame.
  Result<Rect> roi_to_rectified(StereoSide side, Rect roi_original) const;
  Result<Rect> roi_to_original(StereoSide side, Rect roi_rectified) const;

  // World point (mm, calib.json frame) of rectified left pixel (u, v) with
  // disparity d px (right pixel u - d); fails for d <= 0.
  Result<Eigen::Vector3d> point_3d(double u_left, double v, double disparity_px) const {
    return rectified_point(pair_, u_left, v, disparity_px);
  }

 private:
  const TsaiCamera& camera(StereoSide s) const {
    return s == StereoSide::left ? rig_.left : rig_.right;
  }
  const RectifiedCamera& rect(StereoSide s) const {
    return s == StereoSide::left ? pair_.left : pair_.right;
  }
  Status check_rectify(ConstGray8View original, Gray8View rectified, Rect region) const;
  std::span<const RemapEntry> table(StereoSide s) const {
    return s == StereoSide::left ? left_ : right_;
  }

  StereoRig rig_;
  RectifiedPair pair_;
  std::span<const RemapEntry> left_;
  std::span<const RemapEntry> right_;
  int width_ = 0;
  int height_ = 0;
};

// Rectifier::roi_to_rectified without the tables (budget sizing at init).
Result<Rect> roi_to_rectified(const TsaiCamera& cam, const RectifiedCamera& rect, Rect roi,
                              int width, int height);

}  // namespace petra

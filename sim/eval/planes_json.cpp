#include "sim/eval/planes_json.hpp"

#include <vector>

#include "algo/core/json_writer.hpp"
#include "sim/io/json_vec3.hpp"

namespace petra::eval {

namespace {

// The grindability fields of a plane (optional in the contract): verdict,
// uncertainty, the footprint disc and the whole patch's own plane.
void grind_fields(json::Writer& w, const GrindPlane& p, double diameter_mm) {
  w.key("verdict").string(verdict_key(p.verdict));
  w.key("grindable").boolean(p.verdict == PlaneVerdict::accepted);
  w.key("normal_sigma_deg").number(p.normal_sigma_deg);
  w.key("offset_sigma_mm").number(p.offset_sigma_mm);
  w.key("footprint").begin_object();
  w.key("diameter_mm").number(diameter_mm);
  w.key("covered").boolean(p.footprint_coverage > 0);
  w.key("rms_mm").number(p.footprint_rms_mm);
  w.key("peak_to_valley_mm").number(p.footprint_pv_mm);
  w.key("coverage").number(p.footprint_coverage);
  w.key("normal");
  sim::write_vec3(w, p.footprint_normal);
  w.key("agrees").boolean(p.footprint_agrees);
  w.key("plane").string(p.footprint_local ? "footprint" : "face");
  if (p.footprint_reach != FootprintReach::not_asked)
    w.key("reach").string(footprint_reach_key(p.footprint_reach));
  w.end_object();
  w.key("face").begin_object();
  w.key("normal");
  sim::write_vec3(w, p.face_normal);
  w.key("centroid_mm");
  sim::write_vec3(w, p.face_centroid_mm);
  w.end_object();
}

}  // namespace

std::string format_planes_json(const ReconstructionOutput& r, const CalibCheck* calibration,
                               const GrayMapQ8* gray_map) {
  const double grinder_diameter_mm = r.planes.footprint_diameter_mm;
  std::vector<char> buf(4096 + 1536 * static_cast<std::size_t>(r.planes.count));
  json::Writer w(buf);
  w.begin_object();
  w.key("planes").begin_array();
  for (int k = 0; k < r.planes.accepted; ++k) {
    const GrindPlane& p = r.planes.planes[k];
    w.raw("\n ");
    w.begin_object();
    w.key("normal");
    sim::write_vec3(w, p.normal);
    // centroid_mm keeps its contract meaning (the face's area centroid);
    // grind_point_mm is where the grinder goes (the footprint disc's centre).
    w.key("centroid_mm");
    sim::write_vec3(w, p.face_centroid_mm);
    w.key("grind_point_mm");
    sim::write_vec3(w, p.centroid_mm);
    w.key("area_mm2").number(p.area_mm2);
    w.key("rms_mm").number(p.rms_mm);
    w.key("triangles").integer(static_cast<long long>(p.triangles));
    w.key("view_angle_deg").number(p.view_angle_deg);
    grind_fields(w, p, grinder_diameter_mm);
    w.end_object();
  }
  w.end_array();
  w.raw("\n");
  w.key("ground").begin_object();
  w.key("normal");
  sim::write_vec3(w, r.ground.plane.normal);
  w.key("d_mm").number(r.ground.plane.d);
  w.key("rms_mm").number(r.ground.rms_mm);
  w.end_object();
  w.raw("\n");
  // How the rock was segmented (optional field): "ground_plane" or "click_region".
  w.key("segmentation").string(segment_method_name(r.segmentation));
  w.raw("\n");
  // The region grown from the click (optional field, with "click_region").
  if (r.segmentation == SegmentMethod::click_region) {
    w.key("click_region").begin_object();
    w.key("points").integer(static_cast<long long>(r.click_region.points));
    w.key("loosened").integer(r.click_region.loosened);
    w.end_object();
    w.raw("\n");
  }
  // The pair's row alignment (optional field; absent on a replayed disparity map).
  if (calibration != nullptr && calibration->present) {
    w.key("calibration").begin_object();
    w.key("vertical_offset_px").number(calibration->vertical_offset_px);
    w.key("spread_px").number(calibration->spread_px);
    w.key("features").integer(calibration->features);
    w.key("verdict").string(to_string(calibration->verdict));
    if (calibration->verdict == CalibVerdict::corrected)
      w.key("corrected_px").number(calibration->corrected_px);
    w.end_object();
    w.raw("\n");
  }
  // The right view's gray levels as the matcher mapped them (optional field).
  if (gray_map != nullptr) {
    w.key("gray_map").begin_object();
    w.key("gain").number(gray_map->gain_q8 / 256.0);
    w.key("offset").number(gray_map->offset_q8 / 256.0);
    w.end_object();
    w.raw("\n");
  }
  const ReconstructionStats& s = r.stats;
  w.key("stats").begin_object();
  w.key("dense_points").integer(s.dense_points);
  w.key("filtered_points").integer(s.filtered_points);
  w.key("disparity_min").number(s.disparity_min_px);
  w.key("disparity_max").number(s.disparity_max_px);
  w.key("points_3d").integer(static_cast<long long>(s.triangulated));
  w.key("point_stride").integer(s.point_stride);
  w.key("triangles").integer(static_cast<long long>(s.mesh.kept));
  w.key("rock_triangles").integer(static_cast<long long>(s.rock_triangles));
  w.key("ground_points").integer(static_cast<long long>(r.ground.ground_points));
  w.key("rock_points").integer(static_cast<long long>(r.ground.rock_points));
  w.end_object();
  w.raw("\n");
  // Candidates that were not accepted, with the reason (optional field).
  w.key("rejected").begin_array();
  for (int k = r.planes.accepted; k < r.planes.count; ++k) {
    const GrindPlane& p = r.planes.planes[k];
    w.begin_object();
    w.key("reason").string(verdict_name(p.verdict));
    w.key("normal");
    sim::write_vec3(w, p.normal);
    // centroid_mm keeps its contract meaning (the face's area centroid);
    // grind_point_mm is where the grinder goes (the footprint disc's centre).
    w.key("centroid_mm");
    sim::write_vec3(w, p.face_centroid_mm);
    w.key("grind_point_mm");
    sim::write_vec3(w, p.centroid_mm);
    w.key("area_mm2").number(p.area_mm2);
    w.key("rms_mm").number(p.rms_mm);
    grind_fields(w, p, grinder_diameter_mm);
    w.end_object();
  }
  w.end_array();
  w.end_object();
  w.raw("\n");
  auto n = w.finish();
  return n ? std::string(w.view()) : std::string();
}

}  // namespace petra::eval

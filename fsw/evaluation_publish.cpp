// EvaluationService's publishing: a finished run to telemetry, products and
// events, in the order the ground reads them (docs/executive.md "Evaluation").
#include "fsw/evaluation_service.hpp"

namespace petra::fsw {

namespace {}  // namespace

// The selection reported is the one in force now: SELECT_ROI is accepted
// during a run, and EVAL_RESULT has always carried the current one.
tlm::EvalResult EvaluationService::result_summary() const {
  tlm::EvalResult r;
  r.eval_id = eval_id_;
  r.frame = frame_;
  const Rect roi = selection_->roi;
  r.roi_px = {static_cast<std::uint16_t>(roi.x), static_cast<std::uint16_t>(roi.y),
              static_cast<std::uint16_t>(roi.w), static_cast<std::uint16_t>(roi.h)};
  r.planes_requested = static_cast<std::uint8_t>(selection_->planes);
  r.total_ms = elapsed_ms_;
  r.step_us = step_us_;
  return r;
}

bool EvaluationService::publish() {
  const EvalOutput& out = runner_.output();
  const Status& s = runner_.status();
  const tlm::TmTime t = tm_time(w_.clock->realtime_ns());
  elapsed_ms_ = static_cast<std::uint32_t>(elapsed_ns() / hal::kNsPerMs);
  step_us_ = out.step_us;
  if (acquire_us_ != 0) step_us_[static_cast<std::size_t>(Step::ACQUIRE)] = acquire_us_;
  tlm::EvalResult r = result_summary();
  planes_.clear();
  if (!s) {
    r.status = 2;
    r.reason = static_cast<std::uint8_t>(Reason::PIPELINE_ERROR);
    w_.queue->push(r, t);
    w_.events->raise(EventId::EVAL_FAILED, static_cast<std::int32_t>(eval_id_),
                     static_cast<std::int32_t>(s.code()),
                     static_cast<std::int32_t>(out.failed_step));
    return false;
  }
  const int requested = selection_->planes;
  const auto found = static_cast<std::int32_t>(out.planes.size());
  r.planes_found = static_cast<std::uint8_t>(found);
  r.status = found < requested ? 1 : 0;
  r.dense_points = out.dense_points;
  r.filtered_points = out.filtered_points;
  r.disparity_min = out.disparity_min;
  r.disparity_max = out.disparity_max;
  r.segmentation = out.segmentation;
  r.calib_vertical_offset_px = out.calib_vertical_offset_px;
  r.calib_spread_px = out.calib_spread_px;
  r.calib_features = out.calib_features;
  r.calib_verdict = out.calib_verdict;
  r.gray_gain = out.gray_gain;
  r.gray_offset = out.gray_offset;
  r.click_loosened = out.click_loosened;
  w_.queue->push(r, t);
  push_planes(out, t);
  stage_products(out);
  const auto id = static_cast<std::int32_t>(eval_id_);
  w_.events->raise(EventId::EVAL_COMPLETED, id, found, requested,
                   static_cast<std::int32_t>(elapsed_ms_));
  if (r.status == 1)
    w_.events->raise(EventId::FEWER_PLANES, id, found, requested, out.refused_verdict);
  return true;
}

// The ground plane, then each grind plane stamped with its identity and kept for ARM_GOTO.
void EvaluationService::push_planes(const EvalOutput& out, tlm::TmTime t) {
  tlm::GroundPlane g;
  g.eval_id = eval_id_;
  g.normal = out.ground_normal;
  g.d_mm = out.ground_d_mm;
  g.points = out.ground_points;
  w_.queue->push(g, t);
  for (std::size_t i = 0; i < out.planes.size(); ++i) {
    tlm::GrindPlane p = out.planes[i];
    p.eval_id = eval_id_;
    p.rank = static_cast<std::uint8_t>(i);
    p.plane_count = static_cast<std::uint8_t>(out.planes.size());
    w_.queue->push(p, t);
    (void)planes_.push_back(p);
  }
}

void EvaluationService::stage_products(const EvalOutput& out) {
  ProductStreamer& products = *w_.products;
  const int step = w_.params->get_int(ParamId::THUMB_DECIMATION);
  if (!out.disparity_gray.empty())
    products.stage_image(ProductKind::DISPARITY, eval_id_, out.disparity_gray, 1, step);
  if (!out.overlay_rgb.empty())
    products.stage_image(ProductKind::OVERLAY, eval_id_, out.overlay_rgb, 3, step);
  if (!out.cloud_xyz_mm.empty())
    products.stage_cloud(eval_id_, out.cloud_xyz_mm,
                         static_cast<std::size_t>(w_.params->get_int(ParamId::CLOUD_MAX_POINTS)));
}

}  // namespace petra::fsw

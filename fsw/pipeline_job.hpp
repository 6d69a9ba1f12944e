// The narrow interface between the executive and the image pipeline. The
// PipelineRunner owns the memory and the worker thread; a PipelineJob is the
// computation: it states its memory need once at init, then runs one
// evaluation at a time on the worker thread, taking every byte from the arena
// it is given and polling `cancel` between steps. Memory that lives for the
// whole mission (tables built once) is taken in init(); each run gets the
// arena released back to where init() left it.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>

#include "algo/chain/pipeline_request.hpp"
#include "algo/core/arena.hpp"
#include "algo/core/fixed_vector.hpp"
#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"
#include "algo/propose/proposals.hpp"
#include "tlm/telemetry.hpp"
#include "tlm/tlm_defs.hpp"

namespace petra {
struct StereoRig;
}

namespace petra::fsw {

inline constexpr std::size_t kMaxPlanes = 8;
inline constexpr std::size_t kStepSlots = PETRA_STEP_SLOTS;

enum class Step : std::uint8_t {
#define PETRA_STEP_ENUM(NAME, slot) NAME = (slot),
  PETRA_PIPELINE_STEPS(PETRA_STEP_ENUM)
#undef PETRA_STEP_ENUM
};

// The configuration's budget as a job sees it: what it may size itself for.
// (Not algo's PipelineBudget: the flight job derives that one from this.)
struct JobBudget {
  int max_width = 0;
  int max_height = 0;
  std::size_t max_cloud_points = 0;
  std::size_t arena_limit = 0;  // bytes the arena will have (budget.arena_mb); 0: no limit
  // Largest ROI the operator may select, original image px (budget.roi_width,
  // roi_height); 0: the job's default, or the largest that fits arena_limit.
  int max_roi_width = 0;
  int max_roi_height = 0;
  const StereoRig* rig = nullptr;  // sizes the rectified ROI; nullptr: no calib.json
  // Where the arm is (arm.mount): the proposer judges reach with it.
  ::petra::arm::ArmGeometry arm_geometry = ::petra::arm::rover_arm_geometry();
};

// What a job can take, fixed at init; the executive refuses commands beyond
// it (SELECT_ROI, SET_PARAM of the disparity envelope). 0: no limit.
struct JobLimits {
  int roi_width = 0;    // px, original left image
  int roi_height = 0;   // px
  int disparities = 0;  // DISP_MAX_PX - DISP_MIN_PX + 1
};

// What a run computes: the chain on the selected ROI (EVALUATE), or the rock
// proposals over a region of the whole pair (PROPOSE). One at a time: both
// run on the same worker and arena.
enum class JobKind : std::uint8_t { EVALUATE, PROPOSE };

// One evaluation request: the pair, the operator's selection and the
// parameters in force when EVALUATE (or PROPOSE) was accepted.
struct EvalRequest {
  JobKind kind = JobKind::EVALUATE;
  std::uint32_t eval_id = 0;
  std::uint32_t frame = 0;
  ConstGray8View left;
  ConstGray8View right;
  const StereoRig* rig = nullptr;  // nullptr when no calib file is configured
  // SELECT_ROI as built from the command, MATCH_METHOD as method: what Pipeline::run takes.
  PipelineRequest selection;
  int disp_min_px = 0;
  int disp_max_px = 0;
  double shadow_fraction = 0;
  double min_plane_area_mm2 = 0;
  // PROPOSE only: the operator's request (region empty: the whole image).
  ProposalRequest proposal;
  // The arm's pose now (measured joints, or stowed when no arm reports
  // them): both kinds judge the arm's reach from it.
  ::petra::arm::JointVector arm_pose = ::petra::arm::stow_pose();
};

struct EvalOutput {
  // A plane is one type from here to the downlink and the arm target: the
  // job fills what it measured; eval_id, rank and plane_count are stamped
  // when the evaluation is published.
  FixedVector<tlm::GrindPlane, kMaxPlanes> planes;  // ranked, best first
  std::uint8_t refused_verdict = 0;                 // of the largest refused face (0: none refused)
  std::array<double, 3> ground_normal{};
  double ground_d_mm = 0;
  std::uint32_t ground_points = 0;
  std::uint8_t segmentation = 0;       // SegmentMethod: 0 ground plane, 1 click region
  float calib_vertical_offset_px = 0;  // calibration check (algo/camera/calib_check)
  float calib_spread_px = 0;
  std::uint16_t calib_features = 0;
  std::uint8_t calib_verdict = 0;  // CalibVerdict: 0 unknown, 1 ok, 2 drifted, 3 corrected
  float gray_gain = 1;             // the matcher's gray-level map (docs/matching.md step 0)
  float gray_offset = 0;
  std::uint8_t click_loosened = 0;  // ClickRegionResult::loosened (docs/reconstruction.md 5b)
  std::uint32_t dense_points = 0;
  std::uint32_t filtered_points = 0;
  float disparity_min = 0;
  float disparity_max = 0;
  std::array<std::uint32_t, kStepSlots> step_us{};
  Step failed_step = Step::ACQUIRE;  // meaningful when run() fails
  // Products, pointing into the arena (valid until the next run); empty when absent.
  ConstGray8View disparity_gray;              // disparity as 8-bit gray, ROI-sized
  ImageView<const std::uint8_t> overlay_rgb;  // width = 3 * pixels, interleaved RGB
  std::span<const float> cloud_xyz_mm;        // x, y, z per point
  // PROPOSE: the ranked list, in the job's memory (valid until the next run).
  const ProposalList* proposals = nullptr;
};

class PipelineJob {
 public:
  virtual ~PipelineJob() = default;
  virtual const char* name() const = 0;
  // Arena for init() plus the largest run, for this budget (asked once, at init).
  virtual std::size_t arena_bytes(const JobBudget& budget) const = 0;
  // Called once on the worker's arena before any run: what it takes stays
  // allocated for every run. `rig` is nullptr when no calib file is configured.
  // An error stops the executive's init (a configuration the job cannot serve).
  virtual Status init(const JobBudget& budget, const StereoRig* rig, Arena& arena) {
    (void)budget;
    (void)rig;
    (void)arena;
    return {};
  }
  // True when run() serves JobKind::PROPOSE (a proposer was built at init).
  virtual bool can_propose() const { return false; }
  // Valid after init(); read by the loop thread while a run goes on.
  virtual JobLimits limits() const { return {}; }
  // Its memory per stage as text (printed at boot); snprintf-like.
  virtual int describe_memory(char* buf, std::size_t size) const {
    if (size > 0) buf[0] = '\0';
    return 0;
  }
  // Runs one evaluation (request.kind) on the worker thread. `out` starts
  // cleared. A job without a proposer fails a PROPOSE run not_supported.
  virtual Status run(const EvalRequest& request, Arena& arena, const std::atomic<bool>& cancel,
                     EvalOutput& out) = 0;
};

}  // namespace petra::fsw

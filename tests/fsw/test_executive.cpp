// The executive end to end in-process: real UDP on loopback, real file
// camera, the scripted test double in place of the image pipeline.
#include <gtest/gtest.h>

#include <set>

#include "algo/wire/crc16.hpp"
#include "tests/fsw/executive_harness.hpp"

namespace petra::test {
namespace {

using cmd::FunctionCode;

fsw::EvalOutput two_executive_planes() {
  fsw::EvalOutput o;
  tlm::GrindPlane a;
  a.normal = {0.0, -0.6, -0.8};
  a.centroid_mm = {12.5, -30.25, 812.0};
  a.area_mm2 = 1530.5;
  a.flatness_rms_mm = 0.42;
  a.triangles = 311;
  tlm::GrindPlane b = a;
  b.normal = {0.6, 0.0, -0.8};
  b.centroid_mm = {40.0, -10.0, 800.0};
  b.area_mm2 = 900.0;
  b.triangles = 150;
  (void)o.planes.push_back(a);
  (void)o.planes.push_back(b);
  o.ground_normal = {0.0, -1.0, 0.0};
  o.ground_d_mm = 250.0;
  o.ground_points = 1000;
  o.dense_points = 23465;
  o.filtered_points = 21382;
  o.disparity_min = -21;
  o.disparity_max = 20;
  o.gray_gain = 1.176f;
  o.gray_offset = 7.0f;
  o.click_loosened = 1;
  return o;
}

TEST(Executive, BootsToIdleWithBootEventAndHousekeeping) {
  ExecutiveHarness h;
  ASSERT_TRUE(h.boot().ok());
  EXPECT_EQ(h.exec().mode(), Mode::IDLE);
  h.cycles(1);
  EXPECT_TRUE(h.has_event(static_cast<std::uint16_t>(EventId::BOOT_COMPLETE)));
  EXPECT_TRUE(h.has_event(static_cast<std::uint16_t>(EventId::MODE_CHANGED)));
  ASSERT_FALSE(h.all<tlm::Housekeeping>().empty());
  const auto hk = h.all<tlm::Housekeeping>().front();
  EXPECT_EQ(hk.mode, static_cast<std::uint8_t>(Mode::IDLE));
  EXPECT_EQ(hk.memory_bytes, h.exec().memory_bytes());
  EXPECT_EQ(hk.arena_bytes, 1u << 20);
}

TEST(Executive, SelectRoiAndEvaluateDownlinkThePipelinesPlanes) {
  ExecutiveHarness h;
  h.job.script = two_executive_planes();
  ASSERT_TRUE(h.boot().ok());
  const auto sel = h.make(FunctionCode::SELECT_ROI, roi(20, 10, 100, 80, 3));
  cmd::EvaluateArgs ev;
  ev.acquire = 1;
  const auto eval = h.make(FunctionCode::EVALUATE, ev);
  h.send(sel);
  h.send(eval);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(eval.counter, AckStage::COMPLETED); }));
  EXPECT_TRUE(h.has_ack(sel.counter, AckStage::COMPLETED));
  EXPECT_EQ(h.exec().mode(), Mode::IDLE);
  // The job saw the operator's selection.
  EXPECT_EQ(h.job.last_request.selection.roi, (Rect{20, 10, 100, 80}));
  EXPECT_EQ(h.job.last_request.selection.planes, 3);

  const auto results = h.all<tlm::EvalResult>();
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].planes_found, 2);
  EXPECT_EQ(results[0].planes_requested, 3);
  EXPECT_EQ(results[0].status, 1);  // fewer than c qualified
  EXPECT_EQ(results[0].dense_points, 23465u);
  EXPECT_EQ(results[0].gray_gain, 1.176f);  // the matcher's gray-level map, as measured
  EXPECT_EQ(results[0].gray_offset, 7.0f);
  EXPECT_EQ(results[0].click_loosened, 1);  // the click region grown past a groove
  EXPECT_EQ(results[0].step_us[static_cast<std::size_t>(fsw::Step::MATCH)], 40u);
  EXPECT_TRUE(h.has_event(static_cast<std::uint16_t>(EventId::FEWER_PLANES)));

  const auto planes = h.all<tlm::GrindPlane>();
  ASSERT_EQ(planes.size(), 2u);
  const auto want = two_executive_planes();
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(planes[i].rank, i);
    EXPECT_EQ(planes[i].normal, want.planes[i].normal);  // f64 on the wire: exact
    EXPECT_EQ(planes[i].centroid_mm, want.planes[i].centroid_mm);
    EXPECT_EQ(planes[i].area_mm2, want.planes[i].area_mm2);
    EXPECT_EQ(planes[i].triangles, want.planes[i].triangles);
  }
  const auto ground = h.all<tlm::GroundPlane>();
  ASSERT_EQ(ground.size(), 1u);
  EXPECT_EQ(ground[0].d_mm, 250.0);

  // Products: the left image after acquisition, the disparity thumbnail after the run.
  ASSERT_TRUE(h.cycle_until([&] {
    int done = 0;
    for (const auto& p : h.all<tlm::Product>())
      if (p.chunk + 1 == p.chunks) ++done;
    return done >= 2;
  }));
  std::size_t left_bytes = 0;
  for (const auto& p : h.all<tlm::Product>())
    if (p.product == 1) left_bytes += p.data_len;
  EXPECT_EQ(left_bytes,
            static_cast<std::size_t>(ExecutiveHarness::kWidth * ExecutiveHarness::kHeight));
}

TEST(Executive, ProductChunksCarryCcsdsSequenceFlagsAndRebuildTheImage) {
  ExecutiveHarness h;
  ASSERT_TRUE(h.boot().ok());
  const auto acq = h.make(FunctionCode::ACQUIRE);
  h.send(acq);
  ASSERT_TRUE(h.cycle_until([&] {
    for (const auto& p : h.all<tlm::Product>())
      if (p.chunk + 1 == p.chunks) return true;
    return false;
  }));
  std::vector<std::uint8_t> image;
  std::vector<wire::SeqFlags> flags;
  for (const auto& pk : h.received)
    if (const auto* p = std::get_if<tlm::Product>(&pk.body)) {
      image.insert(image.end(), p->data.begin(), p->data.begin() + p->data_len);
      flags.push_back(pk.header.primary.seq_flags);
    }
  ASSERT_EQ(image.size(), 160u * 120u);
  ASSERT_EQ(flags.size(), (160u * 120u + 1023u) / 1024u);
  EXPECT_EQ(flags.front(), wire::SeqFlags::first);
  EXPECT_EQ(flags.back(), wire::SeqFlags::last);
  for (std::size_t i = 1; i + 1 < flags.size(); ++i)
    EXPECT_EQ(flags[i], wire::SeqFlags::continuation);
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x)
      ASSERT_EQ(image[static_cast<std::size_t>(y * 160 + x)],
                static_cast<std::uint8_t>((x * 7 + y * 3) & 0xFF));
}

TEST(Executive, CommandsAndHousekeepingKeepFlowingDuringALongEvaluation) {
  ExecutiveHarness h(R"(,"params":"params.json")");
  std::ofstream(h.dir() / "params.json") << R"({"HK_PERIOD_MS": 100})";
  h.job.hold = true;
  ASSERT_TRUE(h.boot().ok());
  h.send(h.make(FunctionCode::SELECT_ROI, roi(0, 0, 50, 50, 2)));
  cmd::EvaluateArgs ev;
  ev.acquire = 1;
  const auto eval = h.make(FunctionCode::EVALUATE, ev);
  h.send(eval);
  ASSERT_TRUE(h.cycle_until([&] { return h.job.runs.load() == 1; }));
  EXPECT_EQ(h.exec().mode(), Mode::EVALUATE);
  const std::size_t hk_before = h.all<tlm::Housekeeping>().size();
  const auto noop = h.make(FunctionCode::NOOP);
  h.send(noop);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(noop.counter, AckStage::COMPLETED); }));
  ASSERT_TRUE(h.cycle_until([&] { return h.all<tlm::Housekeeping>().size() >= hk_before + 2; }));
  EXPECT_EQ(h.all<tlm::Housekeeping>().back().eval_running, 1);
  // A command not allowed while evaluating is refused, the evaluation goes on.
  const auto acq = h.make(FunctionCode::ACQUIRE);
  h.send(acq);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(acq.counter, AckStage::REJECTED); }));
  EXPECT_EQ(h.acks_for(acq.counter).back().reason, static_cast<std::uint8_t>(Reason::WRONG_MODE));
  // ABORT stops it: the evaluation fails ABORTED, the job saw the cancel.
  const auto abort = h.make(FunctionCode::ABORT);
  h.send(abort);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(abort.counter, AckStage::COMPLETED); }));
  ASSERT_TRUE(h.has_ack(eval.counter, AckStage::FAILED));  // before .back()
  EXPECT_EQ(h.acks_for(eval.counter).back().reason, static_cast<std::uint8_t>(Reason::ABORTED));
  EXPECT_EQ(h.exec().mode(), Mode::IDLE);
  ASSERT_TRUE(h.cycle_until([&] { return h.job.saw_cancel.load(); }));
  EXPECT_TRUE(h.all<tlm::EvalResult>().empty());  // an aborted run publishes nothing
}

TEST(Executive, WithoutAPipelineEvaluateFailsWithNoPipeline) {
  ExecutiveHarness h("", /*with_job=*/false);
  ASSERT_TRUE(h.boot().ok());
  h.send(h.make(FunctionCode::SELECT_ROI, roi(0, 0, 50, 50, 2)));
  const auto eval = h.make(FunctionCode::EVALUATE, cmd::EvaluateArgs{1});
  h.send(eval);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(eval.counter, AckStage::FAILED); }));
  EXPECT_EQ(h.acks_for(eval.counter).back().reason, static_cast<std::uint8_t>(Reason::NO_PIPELINE));
  EXPECT_TRUE(h.all<tlm::GrindPlane>().empty());
  EXPECT_EQ(h.exec().mode(), Mode::IDLE);
}

TEST(Executive, EvaluateBeforeSelectRoiFailsNoRoi) {
  ExecutiveHarness h;
  ASSERT_TRUE(h.boot().ok());
  const auto eval = h.make(FunctionCode::EVALUATE, cmd::EvaluateArgs{1});
  h.send(eval);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(eval.counter, AckStage::FAILED); }));
  EXPECT_EQ(h.acks_for(eval.counter).back().reason, static_cast<std::uint8_t>(Reason::NO_ROI));
}

TEST(Executive, PipelineErrorFailsTheCommandWithAnEvent) {
  ExecutiveHarness h;
  h.job.fail = true;
  ASSERT_TRUE(h.boot().ok());
  h.send(h.make(FunctionCode::SELECT_ROI, roi(0, 0, 50, 50, 2)));
  const auto eval = h.make(FunctionCode::EVALUATE, cmd::EvaluateArgs{1});
  h.send(eval);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(eval.counter, AckStage::FAILED); }));
  EXPECT_EQ(h.acks_for(eval.counter).back().reason,
            static_cast<std::uint8_t>(Reason::PIPELINE_ERROR));
  EXPECT_TRUE(h.has_event(static_cast<std::uint16_t>(EventId::EVAL_FAILED)));
  ASSERT_EQ(h.all<tlm::EvalResult>().size(), 1u);
  EXPECT_EQ(h.all<tlm::EvalResult>()[0].status, 2);
}

TEST(Executive, EvaluationTimeoutAbortsAndEntersSafe) {
  ExecutiveHarness h(R"(,"params":"params.json")");
  std::ofstream(h.dir() / "params.json") << R"({"EVAL_TIMEOUT_S": 1})";
  h.job.hold = true;
  ASSERT_TRUE(h.boot().ok());
  h.send(h.make(FunctionCode::SELECT_ROI, roi(0, 0, 50, 50, 2)));
  const auto eval = h.make(FunctionCode::EVALUATE, cmd::EvaluateArgs{1});
  h.send(eval);
  ASSERT_TRUE(h.cycle_until([&] { return h.exec().mode() == Mode::SAFE; }, 1000));
  EXPECT_TRUE(h.has_event(static_cast<std::uint16_t>(EventId::EVAL_TIMEOUT)));
  EXPECT_TRUE(h.has_ack(eval.counter, AckStage::FAILED));
  ASSERT_TRUE(h.cycle_until([&] { return h.job.saw_cancel.load(); }));
  // Leaving SAFE takes an explicit command.
  cmd::SetModeArgs m;
  m.mode = static_cast<std::uint8_t>(Mode::IDLE);
  const auto back = h.make(FunctionCode::SET_MODE, m);
  h.send(back);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(back.counter, AckStage::COMPLETED); }));
  EXPECT_EQ(h.exec().mode(), Mode::IDLE);
}

TEST(Executive, ParametersSetGetAndDump) {
  ExecutiveHarness h;
  ASSERT_TRUE(h.boot().ok());
  cmd::SetParamArgs s;
  s.param_id = static_cast<std::uint16_t>(ParamId::THUMB_DECIMATION);
  s.value = 2;
  const auto set = h.make(FunctionCode::SET_PARAM, s);
  h.send(set);
  cmd::GetParamArgs g;
  g.param_id = s.param_id;
  const auto get = h.make(FunctionCode::GET_PARAM, g);
  h.send(get);
  const auto dump = h.make(FunctionCode::DUMP_PARAMS);
  h.send(dump);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(dump.counter, AckStage::COMPLETED); }));
  EXPECT_EQ(h.exec().params().get(ParamId::THUMB_DECIMATION), 2.0);
  const auto values = h.all<tlm::ParamValue>();
  ASSERT_EQ(values.size(), 2 + kParamCount);  // SET echo, GET, every parameter
  EXPECT_EQ(values[0].value, 2.0);
  EXPECT_EQ(values[1].value, 2.0);
}

TEST(Executive, DropsAreCountedAndReportedWhenTheQueueOverflows) {
  ExecutiveHarness h(R"(,"params":"params.json")");
  std::ofstream(h.dir() / "params.json") << R"({"HK_PERIOD_MS": 100})";
  h.queue_packets = 32;
  ASSERT_TRUE(h.boot().ok());
  h.cycles(1);
  // 8 commands per cycle x (2 acks + DUMP's 13 values) overflow 32 slots.
  for (int i = 0; i < 8; ++i) h.send(h.make(FunctionCode::DUMP_PARAMS));
  h.cycles(1);
  EXPECT_GT(h.exec().downlink_queue().dropped(), 0u);
  ASSERT_TRUE(h.cycle_until([&] {
    return !h.all<tlm::Housekeeping>().empty() && h.all<tlm::Housekeeping>().back().tlm_dropped > 0;
  }));
  EXPECT_EQ(h.all<tlm::Housekeeping>().back().tlm_dropped, h.exec().downlink_queue().dropped());
  EXPECT_TRUE(h.has_event(static_cast<std::uint16_t>(EventId::TLM_DROPPED)));
}

TEST(Executive, TheCommandCounterSurvivesARebootSoOldCommandsStayReplays) {
  std::vector<std::uint8_t> recorded;
  const auto dir =
      std::filesystem::temp_directory_path() / ("petra_fsw_reboot_" + std::to_string(::getpid()));
  {
    ExecutiveHarness h("", true, dir.string());
    h.keep_dir();
    ASSERT_TRUE(h.boot().ok());
    h.counter = 41;
    const auto noop = h.make(FunctionCode::NOOP);
    recorded = h.packet(noop);
    h.send_raw(recorded);
    ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(noop.counter, AckStage::COMPLETED); }));
  }
  ExecutiveHarness h2("", true, dir.string());
  ASSERT_TRUE(h2.boot().ok());
  EXPECT_EQ(h2.exec().command_counters().last_counter, 42u);
  h2.send_raw(recorded);
  ASSERT_TRUE(h2.cycle_until([&] { return !h2.all<tlm::Ack>().empty(); }));
  EXPECT_EQ(h2.all<tlm::Ack>().back().reason, static_cast<std::uint8_t>(Reason::REPLAY));
}

TEST(Executive, ArmCommandsFailClearlyWithoutAnArm) {
  ExecutiveHarness h;
  ASSERT_TRUE(h.boot().ok());
  const auto go = h.make(FunctionCode::ARM_GOTO);
  h.send(go);
  ASSERT_TRUE(h.cycle_until([&] { return h.has_ack(go.counter, AckStage::FAILED); }));
  EXPECT_EQ(h.acks_for(go.counter).back().reason,
            static_cast<std::uint8_t>(Reason::ARM_UNAVAILABLE));
  EXPECT_EQ(h.exec().mode(), Mode::IDLE);
}

}  // namespace
}  // namespace petra::test

#include "cmd/validator.hpp"

#include "algo/wire/ccsds.hpp"
#include "algo/wire/crc16.hpp"
#include "cmd/param_defs.hpp"

namespace petra::cmd {

namespace {

Verdict reject(Verdict v, Reason r, std::uint16_t detail = 0) {
  v.reason = r;
  v.detail = detail;
  return v;
}

// What the memory budget fixed at boot cannot hold is refused here, with the
// limit as detail, never accepted and failed by the pipeline later.
Verdict check_roi_budget(Verdict v, const SelectRoiArgs& roi, const ValidationContext& ctx) {
  if (ctx.max_roi_width > 0 && roi.w_px > ctx.max_roi_width)
    return reject(v, Reason::ROI_TOO_WIDE, static_cast<std::uint16_t>(ctx.max_roi_width));
  if (ctx.max_roi_height > 0 && roi.h_px > ctx.max_roi_height)
    return reject(v, Reason::ROI_TOO_TALL, static_cast<std::uint16_t>(ctx.max_roi_height));
  return v;
}

Verdict check_envelope_budget(Verdict v, const SetParamArgs& set, const ValidationContext& ctx) {
  if (ctx.max_disparities <= 0) return v;
  double lo = ctx.disp_min_px, hi = ctx.disp_max_px;
  if (set.param_id == static_cast<std::uint16_t>(ParamId::DISP_MIN_PX))
    lo = set.value;
  else if (set.param_id == static_cast<std::uint16_t>(ParamId::DISP_MAX_PX))
    hi = set.value;
  else
    return v;
  if (hi - lo + 1 > ctx.max_disparities)
    return reject(v, Reason::ENVELOPE_TOO_WIDE, static_cast<std::uint16_t>(ctx.max_disparities));
  return v;
}

// PROPOSE's region: all 0 (the whole image) or at least kMinRegionPx a side
// inside the image; detail names the field to change.
constexpr int kMinRegionPx = 32;
Verdict check_propose(Verdict v, const ProposeArgs& p, const ValidationContext& ctx) {
  enum : std::uint16_t { kX = 1, kY = 2, kW = 3, kH = 4, kWeightGrindable = 6 };
  if (p.w_px == 0 && p.h_px == 0) {
    if (p.x_px != 0) return reject(v, Reason::INVALID_ARGUMENT, kX);
    if (p.y_px != 0) return reject(v, Reason::INVALID_ARGUMENT, kY);
  } else {
    if (p.w_px < kMinRegionPx) return reject(v, Reason::INVALID_ARGUMENT, kW);
    if (p.h_px < kMinRegionPx) return reject(v, Reason::INVALID_ARGUMENT, kH);
    if (p.x_px + p.w_px > ctx.image_width)
      return reject(v, Reason::INVALID_ARGUMENT, p.x_px >= ctx.image_width ? kX : kW);
    if (p.y_px + p.h_px > ctx.image_height)
      return reject(v, Reason::INVALID_ARGUMENT, p.y_px >= ctx.image_height ? kY : kH);
  }
  if (p.weight_grindable == 0 && p.weight_reach == 0 && p.weight_certainty == 0 &&
      p.weight_size == 0)
    return reject(v, Reason::INVALID_ARGUMENT, kWeightGrindable);  // "the weights are all 0"
  return v;
}

// Checks that need more than one field or the context; returns NONE when fine.
Verdict check_consistency(Verdict v, const ValidationContext& ctx) {
  if (const auto* roi = std::get_if<SelectRoiArgs>(&v.command.args)) {
    const SelectionRefusal r = selection_refusal(*roi, ctx);
    return r.reason == Reason::NONE ? v : reject(v, r.reason, r.detail);
  } else if (const auto* propose = std::get_if<ProposeArgs>(&v.command.args)) {
    return check_propose(v, *propose, ctx);
  } else if (const auto* set = std::get_if<SetParamArgs>(&v.command.args)) {
    const ParamDesc* p = find_param(set->param_id);
    if (p == nullptr) return reject(v, Reason::INVALID_ARGUMENT, set->param_id);
    if (!param_value_valid(*p, set->value)) return reject(v, Reason::OUT_OF_RANGE, 1);
    return check_envelope_budget(v, *set, ctx);
  } else if (const auto* get = std::get_if<GetParamArgs>(&v.command.args)) {
    if (find_param(get->param_id) == nullptr)
      return reject(v, Reason::INVALID_ARGUMENT, get->param_id);
  } else if (const auto* mode = std::get_if<SetModeArgs>(&v.command.args)) {
    if (!ground_may_request(ctx.mode, static_cast<Mode>(mode->mode)))
      return reject(v, Reason::BAD_TRANSITION, mode->mode);
  }
  return v;
}

}  // namespace

SelectionRefusal selection_refusal(const SelectRoiArgs& roi, const ValidationContext& ctx) {
  const int bad_field = roi.out_of_range();
  if (bad_field >= 0) return {Reason::OUT_OF_RANGE, static_cast<std::uint16_t>(bad_field)};
  if (roi.x_px + roi.w_px > ctx.image_width || roi.y_px + roi.h_px > ctx.image_height)
    return {Reason::INVALID_ARGUMENT, 0};
  if (roi.has_click != 0 && (roi.click_u_px < roi.x_px || roi.click_u_px >= roi.x_px + roi.w_px ||
                             roi.click_v_px < roi.y_px || roi.click_v_px >= roi.y_px + roi.h_px))
    return {Reason::INVALID_ARGUMENT, 6};
  Verdict v = check_roi_budget(Verdict{}, roi, ctx);
  return {v.reason, v.detail};
}

Verdict validate_command(std::span<const std::uint8_t> datagram, const ValidationContext& ctx) {
  Verdict v;
  const std::size_t size = datagram.size();
  if (size < kMinCommandBytes) return reject(v, Reason::TOO_SHORT);
  if (size > kMaxCommandBytes) return reject(v, Reason::TOO_LONG);

  const wire::PrimaryHeader h = wire::read_primary_header(datagram);
  v.function_code = datagram[6];
  if (h.version != 0 || h.type != wire::PacketType::telecommand || !h.secondary_header ||
      h.apid != kCommandApid || h.seq_flags != wire::SeqFlags::unsegmented || datagram[7] != 0)
    return reject(v, Reason::BAD_HEADER);
  if (wire::packet_bytes(h) != size) return reject(v, Reason::LENGTH_MISMATCH);

  const std::uint16_t crc =
      static_cast<std::uint16_t>((datagram[size - 2] << 8) | datagram[size - 1]);
  if (wire::crc16_ccitt(datagram.first(size - kCrcBytes)) != crc) return reject(v, Reason::BAD_CRC);

  if (ctx.key == nullptr) return reject(v, Reason::BAD_AUTH);
  const std::size_t mac_at = size - kCrcBytes - kHmacBytes;
  if (!verify_mac(*ctx.key, datagram.first(mac_at), datagram.subspan(mac_at, kHmacBytes)))
    return reject(v, Reason::BAD_AUTH);

  wire::ByteReader counter_reader(datagram.subspan(8, 4));
  const std::uint32_t counter = counter_reader.u32();
  v.command.counter = counter;  // authentic: worth reporting even when stale
  if (counter <= ctx.last_counter) return reject(v, Reason::REPLAY);
  v.authenticated = true;

  const CommandDesc* desc = find_command(v.function_code);
  if (desc == nullptr) return reject(v, Reason::UNKNOWN_FUNCTION, v.function_code);
  const std::size_t arg_bytes = mac_at - kTcHeaderBytes;
  if (arg_bytes != desc->arg_bytes)
    return reject(v, Reason::BAD_PAYLOAD_LENGTH, static_cast<std::uint16_t>(arg_bytes));

  v.command.code = static_cast<FunctionCode>(desc->code);
  v.command.args = decode_args(v.command.code, datagram.subspan(kTcHeaderBytes, arg_bytes));
  const int bad_field = args_out_of_range(v.command.args);
  if (bad_field >= 0) return reject(v, Reason::OUT_OF_RANGE, static_cast<std::uint16_t>(bad_field));

  v = check_consistency(v, ctx);
  if (!v.ok()) return v;

  if ((desc->allowed_modes & mode_bit(ctx.mode)) == 0)
    return reject(v, Reason::WRONG_MODE, static_cast<std::uint16_t>(ctx.mode));
  return v;
}

}  // namespace petra::cmd

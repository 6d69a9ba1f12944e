#include "sim/ground/tlm_format.hpp"

#include <cstdio>
#include <iterator>
#include <sstream>
#include <string_view>
#include <type_traits>

#include "cmd/commands.hpp"
#include "cmd/param_defs.hpp"
#include "sim/ground/proposals_format.hpp"
#include "tlm/event_defs.hpp"

namespace petra::ground {

namespace {

std::string number(double v) {
  char buf[48];
  std::snprintf(buf, sizeof(buf), "%.17g", v);
  return buf;
}

template <class T>
std::string value_text(const T& v) {
  if constexpr (std::is_floating_point_v<T>) {
    return number(static_cast<double>(v));
  } else {
    return std::to_string(static_cast<long long>(v));
  }
}

std::string fc_name(long v) {
  if (v == 0) return "the executive";
  const cmd::CommandDesc* d = cmd::find_command(static_cast<std::uint8_t>(v));
  return d != nullptr ? d->name : "fc " + std::to_string(v);
}

std::string kind_name(const std::string& kind, long v) {
  if (kind == "mode")
    return v >= 0 && v < kModeCount ? mode_name(static_cast<Mode>(v)) : std::to_string(v);
  if (kind == "reason") return reason_name(static_cast<Reason>(v));
  if (kind == "fc") return fc_name(v);
  if (kind == "empty") return proposal_empty_name(v);
  if (kind == "errc") return errc_name(static_cast<Errc>(v));
  if (kind == "param") {
    const ParamDesc* p = find_param(static_cast<std::uint16_t>(v));
    return p != nullptr ? p->name : std::to_string(v);
  }
  if (kind == "component") {
    static const char* names[] = {"UPLINK",   "PIPELINE", "PRODUCTS", "HOUSEKEEPING",
                                  "DOWNLINK", "WORKER",   "ARM"};
    return v >= 0 && v < 7 ? names[v] : std::to_string(v);
  }
  if (kind == "step") {
    static const char* names[] = {
#define PETRA_STEP_NAME(NAME, slot) #NAME,
        PETRA_PIPELINE_STEPS(PETRA_STEP_NAME)
#undef PETRA_STEP_NAME
    };
    return v >= 0 && v < PETRA_STEP_SLOTS ? names[v] : std::to_string(v);
  }
  return std::to_string(v);
}

const char* packet_name(std::uint16_t apid) {
  const tlm::TmDesc* d = tlm::find_telemetry(apid);
  return d != nullptr ? d->name : "?";
}

}  // namespace

std::string refusal_detail(std::uint8_t function_code, std::uint8_t reason, std::uint16_t detail) {
  const cmd::CommandDesc* c = cmd::find_command(function_code);
  auto field = [&]() -> std::string {
    if (c != nullptr && detail < c->fields.size())
      return std::string("field ") + c->fields[detail].name;
    return "field " + std::to_string(detail);
  };
  const bool param_command =
      function_code == static_cast<std::uint8_t>(cmd::FunctionCode::SET_PARAM) ||
      function_code == static_cast<std::uint8_t>(cmd::FunctionCode::GET_PARAM);
  const bool propose = function_code == static_cast<std::uint8_t>(cmd::FunctionCode::PROPOSE);
  switch (static_cast<Reason>(reason)) {
    case Reason::OUT_OF_RANGE:
      return field();
    case Reason::INVALID_ARGUMENT:
      if (param_command) return "unknown parameter id " + std::to_string(detail);
      if (propose && c != nullptr && detail < c->fields.size() &&
          std::string_view(c->fields[detail].name) == "weight_grindable")
        return "fields weight_grindable .. weight_size: all 0";
      if (propose) return field() + ": region not all 0, under 32 px or outside the image";
      if (function_code == static_cast<std::uint8_t>(cmd::FunctionCode::SELECT_PROPOSAL)) {
        const cmd::CommandDesc* roi = cmd::find_command("SELECT_ROI");
        return std::string("the proposal's ") +
               (detail < roi->fields.size() ? roi->fields[detail].name : "ROI") +
               " (SELECT_ROI's check)";
      }
      return field();
    case Reason::WRONG_MODE:
      return "in mode " + kind_name("mode", detail);
    case Reason::BAD_TRANSITION:
      return "to mode " + kind_name("mode", detail);
    case Reason::UNKNOWN_FUNCTION:
      return "function code " + std::to_string(detail);
    case Reason::BAD_PAYLOAD_LENGTH:
      return std::to_string(detail) + " argument bytes";
    default:
      return detail != 0 ? "detail " + std::to_string(detail) : "";
  }
}

std::string event_text(const tlm::Event& e) {
  const EventDesc* d = find_event(e.event_id);
  if (d == nullptr) return "unknown event " + std::to_string(e.event_id);
  std::string out;
  const std::string text = d->text;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '{') {
      const auto close = text.find('}', i);
      if (close != std::string::npos && close > i + 1 && text[i + 1] >= '0' && text[i + 1] <= '3') {
        const int n = text[i + 1] - '0';
        const std::string kind = close > i + 3 ? text.substr(i + 3, close - i - 3) : "";
        const bool rejection =
            e.event_id > PETRA_REJECT_EVENT_BASE && e.event_id < PETRA_REJECT_EVENT_BASE + 32;
        if (rejection && n == 1 && i >= 7 && text.compare(i - 7, 7, "detail ") == 0) {
          out.erase(out.size() - 7);  // "detail 2" becomes "field planes"
          out += refusal_detail(static_cast<std::uint8_t>(e.args[0]),
                                static_cast<std::uint8_t>(e.event_id - PETRA_REJECT_EVENT_BASE),
                                static_cast<std::uint16_t>(e.args[1]));
        } else {
          out += kind_name(kind, e.args[static_cast<std::size_t>(n)]);
        }
        i = close;
        continue;
      }
    }
    out += text[i];
  }
  return out;
}

std::string format_line(const tlm::TmPacket& p, std::uint32_t missing_before) {
  std::ostringstream o;
  char t[40];
  std::snprintf(t, sizeof(t), "%u.%06u", p.header.time.seconds, p.header.time.micros);
  o << t << " " << packet_name(p.header.primary.apid) << " #" << p.header.primary.seq_count << " ";
  if (missing_before > 0) o << "(GAP: " << missing_before << " missing before) ";
  std::visit(
      [&](const auto& b) {
        using B = std::decay_t<decltype(b)>;
        if constexpr (std::is_same_v<B, std::monostate>) {
        } else if constexpr (std::is_same_v<B, tlm::Event>) {
          const EventDesc* d = find_event(b.event_id);
          o << severity_name(static_cast<Severity>(b.severity)) << " "
            << (d != nullptr ? d->name : "?") << ": " << event_text(b);
        } else if constexpr (std::is_same_v<B, tlm::Ack>) {
          o << fc_name(b.function_code) << " counter " << b.counter << " "
            << ack_stage_name(static_cast<AckStage>(b.stage));
          if (b.reason != 0) {
            o << " " << reason_name(static_cast<Reason>(b.reason));
            const std::string why = refusal_detail(b.function_code, b.reason, b.detail);
            if (!why.empty()) o << " (" << why << ")";
          }
        } else if constexpr (std::is_same_v<B, tlm::ParamValue>) {
          const ParamDesc* d = find_param(b.param_id);
          o << (d != nullptr ? d->name : "?") << " = " << number(b.value) << " "
            << (d != nullptr ? d->unit : "");
        } else if constexpr (std::is_same_v<B, tlm::Product>) {
          o << "product " << unsigned{b.product} << " id " << b.id << " chunk " << b.chunk + 1
            << "/" << b.chunks << " (" << b.total_bytes << " bytes, " << b.width << "x" << b.height
            << ")";
        } else if constexpr (std::is_same_v<B, tlm::Proposals>) {
          o << format_proposals(b);
        } else if constexpr (std::is_same_v<B, tlm::ProposalPlanes>) {
          o << format_proposal_planes(b);
        } else if constexpr (std::is_same_v<B, tlm::GrindPlane>) {
          static constexpr const char* kReach[] = {
              "", "", "; grind point moved: the most level flat disc is out of the arm's reach",
              "; the arm reaches no flat disc"};
          char buf[448];
          std::snprintf(
              buf, sizeof(buf),
              "eval %u rank %u/%u normal (%.4f, %.4f, %.4f) centroid (%.2f, %.2f, %.2f) mm "
              "area %.1f mm2 flatness %.3f mm, %u triangles; footprint %.0f mm RMS %.3f mm "
              "(%s plane), sigma %.2f deg %.2f mm%s",
              b.eval_id, b.rank, b.plane_count, b.normal[0], b.normal[1], b.normal[2],
              b.centroid_mm[0], b.centroid_mm[1], b.centroid_mm[2], b.area_mm2, b.flatness_rms_mm,
              b.triangles, static_cast<double>(b.footprint_diameter_mm),
              static_cast<double>(b.footprint_rms_mm), b.plane_source == 1 ? "disc's" : "face's",
              static_cast<double>(b.normal_sigma_deg), static_cast<double>(b.offset_sigma_mm),
              kReach[b.footprint_reach < std::size(kReach) ? b.footprint_reach : 0]);
          o << buf;
        } else {
          bool first = true;
          b.each([&](const char* name, const auto& v) {
            if (!first) o << " ";
            first = false;
            o << name << "=";
            using V = std::decay_t<decltype(v)>;
            if constexpr (std::is_arithmetic_v<V>) {
              if (std::string(name) == "mode")
                o << kind_name("mode", static_cast<long>(v));
              else
                o << value_text(v);
            } else {
              o << "[";
              for (std::size_t i = 0; i < v.size(); ++i) o << (i ? "," : "") << value_text(v[i]);
              o << "]";
            }
          });
        }
      },
      p.body);
  return o.str();
}

std::string format_json(const tlm::TmPacket& p, std::uint32_t missing_before) {
  std::ostringstream o;
  o << "{\"apid\":" << p.header.primary.apid << ",\"packet\":\""
    << packet_name(p.header.primary.apid) << "\",\"seq\":" << p.header.primary.seq_count;
  if (missing_before > 0) o << ",\"missing_before\":" << missing_before;
  o << ",\"seq_flags\":" << static_cast<unsigned>(p.header.primary.seq_flags)
    << ",\"time\":" << p.header.time.seconds << ".";
  char us[8];
  std::snprintf(us, sizeof(us), "%06u", p.header.time.micros);
  o << us << ",\"fields\":{";
  std::visit(
      [&](const auto& b) {
        using B = std::decay_t<decltype(b)>;
        if constexpr (!std::is_same_v<B, std::monostate>) {
          bool first = true;
          b.each([&](const char* name, const auto& v) {
            o << (first ? "" : ",") << "\"" << name << "\":";
            first = false;
            using V = std::decay_t<decltype(v)>;
            if constexpr (std::is_arithmetic_v<V>) {
              o << value_text(v);
            } else if constexpr (std::is_same_v<typename V::value_type, std::uint8_t> &&
                                 std::tuple_size_v<V> > 64) {
              static const char* digits = "0123456789abcdef";
              o << "\"";
              for (std::uint8_t x : v) o << digits[x >> 4] << digits[x & 15];
              o << "\"";
            } else {
              o << "[";
              for (std::size_t i = 0; i < v.size(); ++i) o << (i ? "," : "") << value_text(v[i]);
              o << "]";
            }
          });
          if constexpr (std::is_same_v<B, tlm::Ack>)
            o << ",\"detail_text\":\"" << refusal_detail(b.function_code, b.reason, b.detail)
              << "\"";  // names only: nothing to escape
          if constexpr (std::is_same_v<B, tlm::Event>) {
            std::string text = event_text(b);
            std::string esc;
            for (char c : text) {
              if (c == '"' || c == '\\') esc += '\\';
              esc += c;
            }
            o << ",\"text\":\"" << esc << "\"";
          }
        }
      },
      p.body);
  o << "}}";
  return o.str();
}

}  // namespace petra::ground

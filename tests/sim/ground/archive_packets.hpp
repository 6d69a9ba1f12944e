// A synthetic telemetry pass for the archive tests: packet k of a pass is one
// of six kinds (HK, EVENT of severity k % 5, ACK, PARAM_VALUE, EVAL_RESULT,
// GRIND_PLANE), spacecraft time 1000 s + 10 ms * k.
#pragma once

#include <cstdint>
#include <vector>

#include "tlm/telemetry.hpp"

namespace petra::ground::testing {

inline std::vector<std::uint8_t> pass_packet(int k) {
  std::vector<std::uint8_t> out(tlm::kMaxTmBytes);
  const tlm::TmTime t{1000u + static_cast<std::uint32_t>(k / 100),
                      static_cast<std::uint32_t>((k % 100) * 10000)};
  const auto seq = static_cast<std::uint16_t>(k & 0x3FFF);
  const auto flags = wire::SeqFlags::unsegmented;
  std::size_t n = 0;
  switch (k % 6) {
    case 0: {
      tlm::Housekeeping hk;
      hk.uptime_s = static_cast<std::uint32_t>(k);
      n = tlm::encode_tm(hk, seq, flags, t, out);
      break;
    }
    case 1: {
      tlm::Event e;
      e.event_id = 1;
      e.severity = static_cast<std::uint8_t>(k % 5);
      n = tlm::encode_tm(e, seq, flags, t, out);
      break;
    }
    case 2: {
      tlm::Ack a;
      a.function_code = 0x12;
      a.counter = static_cast<std::uint32_t>(k);
      a.stage = 3;
      n = tlm::encode_tm(a, seq, flags, t, out);
      break;
    }
    case 3: {
      tlm::ParamValue v;
      v.param_id = 1;
      v.value = k;
      n = tlm::encode_tm(v, seq, flags, t, out);
      break;
    }
    case 4: {
      tlm::EvalResult r;
      r.eval_id = static_cast<std::uint32_t>(k);
      n = tlm::encode_tm(r, seq, flags, t, out);
      break;
    }
    default: {
      tlm::GrindPlane g;
      g.eval_id = static_cast<std::uint32_t>(k);
      g.normal = {0.f, 0.f, 1.f};
      n = tlm::encode_tm(g, seq, flags, t, out);
      break;
    }
  }
  out.resize(n);
  return out;
}

}  // namespace petra::ground::testing

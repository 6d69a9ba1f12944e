#include "hal/canopen/cia301.hpp"

namespace petra::canopen {

namespace {

void put_u16(std::uint8_t* p, std::uint16_t v) {
  p[0] = static_cast<std::uint8_t>(v);
  p[1] = static_cast<std::uint8_t>(v >> 8);
}
void put_u32(std::uint8_t* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
std::uint16_t get_u16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>(p[0] | (p[1] << 8));
}
std::uint32_t get_u32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}

CanFrame frame(std::uint32_t id, std::uint8_t len) {
  CanFrame f;
  f.id = id;
  f.len = len;
  return f;
}

Status expect_plain(const CanFrame& f, const char* what) {
  if (f.extended || f.rtr)
    return Error::make(Errc::parse_error, "%s: extended or remote frame", what);
  return ok_status();
}

CanFrame make_sdo(std::uint32_t id, const SdoMessage& m) {
  CanFrame f = frame(id, 8);
  const std::uint8_t size = (m.size >= 1 && m.size <= 4) ? m.size : 4;
  const auto n = static_cast<std::uint8_t>((4 - size) << 2);  // unused bytes
  switch (m.kind) {
    case SdoKind::download_request:
      f.data[0] = static_cast<std::uint8_t>(0x23 | n);
      break;
    case SdoKind::download_response:
      f.data[0] = 0x60;
      break;
    case SdoKind::upload_request:
      f.data[0] = 0x40;
      break;
    case SdoKind::upload_response:
      f.data[0] = static_cast<std::uint8_t>(0x43 | n);
      break;
    case SdoKind::abort:
      f.data[0] = 0x80;
      break;
  }
  put_u16(&f.data[1], m.address.index);
  f.data[3] = m.address.subindex;
  const bool carries_value = m.kind == SdoKind::download_request ||
                             m.kind == SdoKind::upload_response || m.kind == SdoKind::abort;
  if (carries_value) {
    std::uint32_t v = m.value;
    if (m.kind != SdoKind::abort && size < 4) v &= (1u << (8 * size)) - 1u;
    put_u32(&f.data[4], v);
  }
  return f;
}

}  // namespace

CobId split_cob_id(std::uint32_t id) {
  CobId c;
  if (id > 0x7FF) return c;
  const auto node = static_cast<std::uint8_t>(id & 0x7F);
  const std::uint32_t fn = id & 0x780;
  c.node = node;
  c.known = true;
  if (id == 0x000) {
    c.function = Function::nmt;
  } else if (id == 0x080) {
    c.function = Function::sync;
    // Node 0 is refused before the function table (as the final else does
    // for unknown functions), on purpose: the order is the rule.
    // NOLINTNEXTLINE(bugprone-branch-clone)
  } else if (node == 0) {
    c.known = false;
  } else if (fn == 0x080) {
    c.function = Function::emcy;
  } else if (fn == 0x180) {
    c.function = Function::tpdo1;
  } else if (fn == 0x200) {
    c.function = Function::rpdo1;
  } else if (fn == 0x580) {
    c.function = Function::sdo_tx;
  } else if (fn == 0x600) {
    c.function = Function::sdo_rx;
  } else if (fn == 0x700) {
    c.function = Function::heartbeat;
  } else {
    c.known = false;
  }
  return c;
}

CanFrame make_nmt(NmtCommand command, std::uint8_t node) {
  CanFrame f = frame(0x000, 2);
  f.data[0] = static_cast<std::uint8_t>(command);
  f.data[1] = node;
  return f;
}

Result<NmtCommand> parse_nmt(const CanFrame& f, std::uint8_t& node) {
  PETRA_TRY(expect_plain(f, "nmt"));
  if (f.id != 0x000 || f.len != 2)
    return Error::make(Errc::parse_error, "nmt: id 0x%X length %u", f.id, f.len);
  const std::uint8_t cs = f.data[0];
  if (cs != 0x01 && cs != 0x02 && cs != 0x80 && cs != 0x81 && cs != 0x82) {
    return Error::make(Errc::parse_error, "nmt: unknown command 0x%02X", cs);
  }
  if (f.data[1] > kMaxNodeId)
    return Error::make(Errc::parse_error, "nmt: node %u > 127", f.data[1]);
  node = f.data[1];
  return static_cast<NmtCommand>(cs);
}

CanFrame make_sync() {
  return frame(0x080, 0);
}

const char* nmt_state_name(NmtState state) {
  switch (state) {
    case NmtState::boot_up:
      return "boot_up";
    case NmtState::stopped:
      return "stopped";
    case NmtState::operational:
      return "operational";
    case NmtState::preoperational:
      return "preoperational";
  }
  return "unknown";
}

CanFrame make_heartbeat(std::uint8_t node, NmtState state) {
  CanFrame f = frame(cob_id(Function::heartbeat, node), 1);
  f.data[0] = static_cast<std::uint8_t>(state);
  return f;
}

Result<NmtState> parse_heartbeat(const CanFrame& f) {
  PETRA_TRY(expect_plain(f, "heartbeat"));
  if (f.len != 1)
    return Error::make(Errc::parse_error, "heartbeat 0x%X: length %u, expected 1", f.id, f.len);
  const std::uint8_t s = f.data[0] & 0x7F;  // bit 7 is the node-guarding toggle
  if (s != 0x00 && s != 0x04 && s != 0x05 && s != 0x7F) {
    return Error::make(Errc::parse_error, "heartbeat 0x%X: unknown state 0x%02X", f.id, s);
  }
  return static_cast<NmtState>(s);
}

CanFrame make_sdo_request(std::uint8_t node, const SdoMessage& m) {
  return make_sdo(cob_id(Function::sdo_rx, node), m);
}

CanFrame make_sdo_response(std::uint8_t node, const SdoMessage& m) {
  return make_sdo(cob_id(Function::sdo_tx, node), m);
}

Result<SdoMessage> parse_sdo(const CanFrame& f, bool from_server) {
  PETRA_TRY(expect_plain(f, "sdo"));
  if (f.len != 8)
    return Error::make(Errc::parse_error, "sdo 0x%X: length %u, expected 8", f.id, f.len);
  SdoMessage m;
  m.address.index = get_u16(&f.data[1]);
  m.address.subindex = f.data[3];
  const std::uint8_t cmd = f.data[0];
  const std::uint8_t ccs = cmd >> 5;
  if (cmd == 0x80) {
    m.kind = SdoKind::abort;
    m.value = get_u32(&f.data[4]);
    return m;
  }
  // Expedited transfers carry e = 1 (bit 1); s (bit 0) says whether n is valid.
  auto expedited_value = [&](SdoMessage& out) -> Status {
    if ((cmd & 0x02) == 0)
      return Error::make(Errc::parse_error, "sdo 0x%X: segmented transfer not supported", f.id);
    out.size = (cmd & 0x01) ? static_cast<std::uint8_t>(4 - ((cmd >> 2) & 0x03)) : 0;
    const std::uint32_t raw = get_u32(&f.data[4]);
    out.value = (out.size == 0 || out.size == 4) ? raw : raw & ((1u << (8 * out.size)) - 1u);
    return ok_status();
  };
  if (from_server) {
    if (ccs == 3 && (cmd & 0x1F) == 0) {
      m.kind = SdoKind::download_response;
      return m;
    }
    if (ccs == 2) {
      m.kind = SdoKind::upload_response;
      PETRA_TRY(expedited_value(m));
      return m;
    }
  } else {
    if (ccs == 1) {
      m.kind = SdoKind::download_request;
      PETRA_TRY(expedited_value(m));
      return m;
    }
    if (ccs == 2 && (cmd & 0x1F) == 0) {
      m.kind = SdoKind::upload_request;
      return m;
    }
  }
  return Error::make(Errc::parse_error, "sdo 0x%X: command byte 0x%02X not supported", f.id, cmd);
}

CanFrame make_emcy(std::uint8_t node, const Emergency& e) {
  CanFrame f = frame(cob_id(Function::emcy, node), 8);
  put_u16(&f.data[0], e.error_code);
  f.data[2] = e.error_register;
  for (int i = 0; i < 5; ++i) f.data[3 + i] = e.vendor[i];
  return f;
}

Result<Emergency> parse_emcy(const CanFrame& f) {
  PETRA_TRY(expect_plain(f, "emcy"));
  if (f.len != 8)
    return Error::make(Errc::parse_error, "emcy 0x%X: length %u, expected 8", f.id, f.len);
  Emergency e;
  e.error_code = get_u16(&f.data[0]);
  e.error_register = f.data[2];
  for (int i = 0; i < 5; ++i) e.vendor[i] = f.data[3 + i];
  return e;
}

CanFrame make_rpdo1(std::uint8_t node, const Rpdo1& p) {
  CanFrame f = frame(cob_id(Function::rpdo1, node), kPdoLength);
  put_u16(&f.data[0], p.controlword);
  put_u32(&f.data[2], static_cast<std::uint32_t>(p.target_position));
  return f;
}

Result<Rpdo1> parse_rpdo1(const CanFrame& f) {
  PETRA_TRY(expect_plain(f, "rpdo1"));
  if (f.len != kPdoLength)
    return Error::make(Errc::parse_error, "rpdo1 0x%X: length %u, expected 6", f.id, f.len);
  Rpdo1 p;
  p.controlword = get_u16(&f.data[0]);
  p.target_position = static_cast<std::int32_t>(get_u32(&f.data[2]));
  return p;
}

CanFrame make_tpdo1(std::uint8_t node, const Tpdo1& p) {
  CanFrame f = frame(cob_id(Function::tpdo1, node), kPdoLength);
  put_u16(&f.data[0], p.statusword);
  put_u32(&f.data[2], static_cast<std::uint32_t>(p.position_actual));
  return f;
}

Result<Tpdo1> parse_tpdo1(const CanFrame& f) {
  PETRA_TRY(expect_plain(f, "tpdo1"));
  if (f.len != kPdoLength)
    return Error::make(Errc::parse_error, "tpdo1 0x%X: length %u, expected 6", f.id, f.len);
  Tpdo1 p;
  p.statusword = get_u16(&f.data[0]);
  p.position_actual = static_cast<std::int32_t>(get_u32(&f.data[2]));
  return p;
}

}  // namespace petra::canopen

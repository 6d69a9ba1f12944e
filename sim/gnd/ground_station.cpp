#include "sim/gnd/ground_station.hpp"

#include <sstream>
#include <type_traits>
#include <vector>

#include "algo/wire/reasons.hpp"
#include "cmd/command_packet.hpp"
#include "cmd/mode.hpp"
#include "sim/gnd/json_text.hpp"
#include "sim/gnd/proposal_pick.hpp"
#include "sim/ground/command_builder.hpp"
#include "sim/ground/tlm_format.hpp"
#include "sim/io/image_io.hpp"
#include "tlm/event_defs.hpp"

namespace petra::gnd {

namespace {

const char* command_name(std::uint8_t code) {
  const cmd::CommandDesc* d = cmd::find_command(code);
  return d != nullptr ? d->name : "?";
}

std::string names_of(const tlm::TmPacket& p) {
  std::ostringstream o;
  o << "{";
  if (const auto* a = std::get_if<tlm::Ack>(&p.body)) {
    o << "\"command\":" << json_string(command_name(a->function_code))
      << ",\"stage\":" << json_string(ack_stage_name(static_cast<AckStage>(a->stage)))
      << ",\"reason\":" << json_string(reason_name(static_cast<Reason>(a->reason)))
      << ",\"detail\":"
      << json_string(ground::refusal_detail(a->function_code, a->reason, a->detail));
  } else if (const auto* e = std::get_if<tlm::Event>(&p.body)) {
    const EventDesc* d = find_event(e->event_id);
    o << "\"event\":" << json_string(d != nullptr ? d->name : "?")
      << ",\"severity\":" << json_string(severity_name(static_cast<Severity>(e->severity)));
  } else if (const auto* l = std::get_if<tlm::Proposals>(&p.body)) {
    const std::string names = proposals_names_json(*l);  // {...}: its members join these
    o << names.substr(1, names.size() - 2);
  } else if (const auto* h = std::get_if<tlm::Housekeeping>(&p.body)) {
    o << "\"mode\":" << json_string(mode_name(static_cast<Mode>(h->mode)))
      << ",\"last_command\":" << json_string(command_name(h->last_function_code))
      << ",\"last_reason\":" << json_string(reason_name(static_cast<Reason>(h->last_reason)));
  }
  o << "}";
  return o.str();
}

// The arguments as signed, {"field": value, ...}.
std::string args_json(const cmd::Command& c) {
  std::ostringstream o;
  o << "{";
  bool first = true;
  std::visit(
      [&](const auto& args) {
        if constexpr (!std::is_same_v<std::decay_t<decltype(args)>, std::monostate>) {
          args.each([&](const char* name, const auto& v) {
            if constexpr (std::is_arithmetic_v<std::decay_t<decltype(v)>>) {
              o << (first ? "" : ",") << json_string(name) << ":" << +v;
              first = false;
            }
          });
        }
      },
      c.args);
  o << "}";
  return o.str();
}

}  // namespace

std::string packet_names_json(const tlm::TmPacket& p) {
  return names_of(p);
}

Status GroundStation::start(const StationOptions& options) {
  options_ = options;
  PETRA_TRY(arm::validate_geometry(options.arm_geometry));
  arm_model_ = ArmModel(options.arm_geometry);
  PETRA_TRY(cmd::auth_init());
  auto key = ground::load_uplink_key(options.key_path);
  if (!key) return key.error();
  key_ = *key;
  if (options.cmd_port < 1 || options.cmd_port > 65535)
    return Error::make(Errc::out_of_range, "--cmd-port %d: outside 1..65535", options.cmd_port);
  if (options.tlm_port < 0 || options.tlm_port > 65535)
    return Error::make(Errc::out_of_range, "--tlm-port %d: outside 0..65535", options.tlm_port);
  if (!options.left_image.empty()) {
    auto img = io::read_gray_image(options.left_image);
    if (!img) return img.error();
    ground::Product p;
    p.kind = 1;
    p.format = 1;
    p.width = img->width;
    p.height = img->height;
    p.bytes.assign(img->pixels.begin(), img->pixels.end());
    keep_product(std::move(p));
  }
  if (!options.archive_path.empty()) {
    auto a = ground::TlmArchive::open(options.archive_path);
    if (!a) return a.error();
    archive_ = std::move(*a);
  }
  PETRA_TRY(uplink_.open("0.0.0.0", 0));
  PETRA_TRY(
      uplink_.set_peer(options.fsw_host.c_str(), static_cast<std::uint16_t>(options.cmd_port)));
  PETRA_TRY(downlink_.open(options.tlm_host.c_str(), static_cast<std::uint16_t>(options.tlm_port)));
  downlink_.set_receive_buffer(8 << 20);  // products arrive in bursts of chunks
  running_ = true;
  thread_ = std::thread([this] { receive_loop(); });
  return {};
}

void GroundStation::stop() {
  running_ = false;
  if (thread_.joinable()) thread_.join();
  archive_.reset();  // commits the last packets
  hub_.close();
}

// raw empty: commit what is pending (a quiet link).
void GroundStation::archive(std::span<const std::uint8_t> raw, const tlm::TmPacket* p) {
  if (!archive_) return;
  const Status s = p != nullptr ? archive_->add(raw, *p, ground::unix_now_s()) : archive_->flush();
  if (!s) {
    ++archive_errors_;
    hub_.publish("archive_error", "{\"error\":" + json_string(s.error().message) + "}");
  }
}

Result<std::uint32_t> GroundStation::send(cmd::Command c) {
  std::lock_guard lock(send_mutex_);  // counters must reach the link in order
  const std::string counter_path =
      options_.counter_path.empty() ? options_.key_path + ".counter" : options_.counter_path;
  auto next = ground::next_counter(counter_path);
  if (!next) return next.error();
  c.counter = *next;
  std::vector<std::uint8_t> packet(cmd::kMaxCommandBytes);
  auto n =
      cmd::encode_command_packet(c, static_cast<std::uint16_t>(c.counter & 0x3FFF), key_, packet);
  if (!n) return n.error();
  if (uplink_.send(std::span(packet).first(*n)) != hal::SendResult::sent)
    return Error::make(Errc::io_error, "uplink: sending %s failed",
                       command_name(static_cast<std::uint8_t>(c.code)));
  const auto code = static_cast<unsigned>(c.code);
  hub_.publish("sent",
               "{\"command\":" + json_string(command_name(static_cast<std::uint8_t>(code))) +
                   ",\"code\":" + std::to_string(code) +
                   ",\"counter\":" + std::to_string(c.counter) + ",\"args\":" + args_json(c) + "}");
  return c.counter;
}

std::optional<ground::Product> GroundStation::product(std::uint8_t kind) const {
  std::lock_guard lock(products_mutex_);
  const auto it = products_.find(kind);
  if (it == products_.end()) return std::nullopt;
  return it->second;
}

std::array<double, arm::kJointCount> GroundStation::arm_joints_deg() const {
  std::lock_guard lock(arm_mutex_);
  return arm_joints_deg_;
}

void GroundStation::keep_product(ground::Product p) {
  std::ostringstream o;
  o << "{\"kind\":" << json_string(ground::product_name(p.kind)) << ",\"id\":" << p.id
    << ",\"width\":" << p.width << ",\"height\":" << p.height
    << ",\"format\":" << unsigned{p.format} << ",\"bytes\":" << p.bytes.size() << "}";
  {
    std::lock_guard lock(products_mutex_);
    products_[p.kind] = std::move(p);
  }
  hub_.publish("product", o.str());
}

void GroundStation::publish_packet(const tlm::TmPacket& p) {
  const std::uint32_t missing = seqs_.observe(p);  // a lost packet shows in the line
  if (const auto* chunk = std::get_if<tlm::Product>(&p.body)) {
    if (auto done = assembler_.add(*chunk)) keep_product(std::move(*done));
    return;
  }
  std::string extra;
  if (const auto* l = std::get_if<tlm::Proposals>(&p.body)) {
    std::lock_guard lock(proposals_mutex_);
    proposals_ = *l;
  }
  if (const auto* a = std::get_if<tlm::ArmStatus>(&p.body)) {
    std::array<double, arm::kJointCount> q{};
    for (std::size_t k = 0; k < q.size(); ++k) q[k] = static_cast<double>(a->joint_deg[k]);
    {
      std::lock_guard lock(arm_mutex_);
      arm_joints_deg_ = q;
    }
    extra = ",\"skeleton\":" + arm_model_.skeleton_json(q);
  }
  hub_.publish("tlm", "{\"tlm\":" + ground::format_json(p, missing) +
                          ",\"line\":" + json_string(ground::format_line(p, missing)) +
                          ",\"names\":" + names_of(p) + extra + "}");
}

std::optional<tlm::Proposals> GroundStation::last_proposals() const {
  std::lock_guard lock(proposals_mutex_);
  return proposals_;
}

void GroundStation::receive_loop() {
  std::vector<std::uint8_t> buf(70000);
  while (running_) {
    auto n = downlink_.receive_wait(buf, 100);
    if (!n || !n->got) {
      archive({}, nullptr);  // a quiet link: what came is on disk
      continue;
    }
    const auto raw = std::span(buf).first(std::min(n->size, buf.size()));
    auto p = tlm::decode_tm(raw);
    if (!p) {
      ++bad_packets_;
      hub_.publish("bad_packet", "{\"error\":" + json_string(p.error().message) + "}");
      continue;
    }
    ++packets_;
    archive(raw, &*p);
    publish_packet(*p);
  }
}

}  // namespace petra::gnd

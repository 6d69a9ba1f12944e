#include "sim/gnd/telemetry_history.hpp"

#include <cstdio>
#include <memory>
#include <sstream>
#include <type_traits>

#include "sim/gnd/ground_station.hpp"
#include "sim/gnd/json_text.hpp"
#include "sim/ground/seq_tracker.hpp"
#include "sim/ground/tlm_archive.hpp"
#include "sim/ground/tlm_format.hpp"
#include "tlm/telemetry.hpp"

namespace petra::gnd {

namespace {

const tlm::TmDesc* find_packet(const std::string& name) {
  for (const tlm::TmDesc& d : tlm::telemetry_table())
    if (name == d.name) return &d;
  return nullptr;
}

bool plottable(const tlm::TmDesc& d) {
  return d.apid != static_cast<std::uint16_t>(tlm::Apid::PRODUCT);
}

// Spacecraft time in ms to the microsecond (%g would round 13-digit times to seconds).
std::string time_ms(double scet_s) {
  char t[32];
  std::snprintf(t, sizeof t, "%.3f", scet_s * 1000.0);
  return t;
}

Result<std::unique_ptr<ground::TlmArchive>> open_archive(const std::string& path, double start_ms,
                                                         double end_ms) {
  if (path.empty())
    return Error::make(Errc::not_ready, "history: the station keeps no archive (--archive FILE)");
  if (!(end_ms >= start_ms))
    return Error::make(Errc::invalid_argument, "history: end before start");
  return ground::TlmArchive::open(path);
}

std::string sample_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

// The value of `field` ("name" or "name[k]") in a decoded packet.
bool field_value(const tlm::TmPacket& p, const std::string& field, double& out) {
  bool found = false;
  std::visit(
      [&](const auto& b) {
        if constexpr (!std::is_same_v<std::decay_t<decltype(b)>, std::monostate>) {
          b.each([&](const char* name, const auto& v) {
            using V = std::decay_t<decltype(v)>;
            if constexpr (std::is_arithmetic_v<V>) {
              if (field == name) {
                out = static_cast<double>(v);
                found = true;
              }
            } else {
              for (std::size_t k = 0; k < v.size(); ++k)
                if (field == std::string(name) + "[" + std::to_string(k) + "]") {
                  out = static_cast<double>(v[k]);
                  found = true;
                }
            }
          });
        }
      },
      p.body);
  return found;
}

}  // namespace

std::string dictionary_json() {
  std::ostringstream o;
  o << "{\"packets\":[";
  bool first = true;
  for (const tlm::TmDesc& d : tlm::telemetry_table()) {
    if (!plottable(d)) continue;
    o << (first ? "" : ",") << "{\"name\":" << json_string(d.name) << ",\"apid\":" << d.apid
      << ",\"description\":" << json_string(d.description) << ",\"points\":[";
    first = false;
    bool first_point = true;
    for (const wire::FieldDesc& f : d.fields) {
      for (std::uint16_t k = 0; k < f.count; ++k) {
        const std::string key = f.count == 1 ? std::string(f.name)
                                             : std::string(f.name) + "[" + std::to_string(k) + "]";
        o << (first_point ? "" : ",") << "{\"key\":" << json_string(key)
          << ",\"unit\":" << json_string(f.unit) << ",\"min\":" << sample_number(f.min)
          << ",\"max\":" << sample_number(f.max)
          << ",\"description\":" << json_string(f.description) << "}";
        first_point = false;
      }
    }
    o << "]}";
  }
  o << "]}";
  return o.str();
}

Result<std::string> history_json(const std::string& archive_path, const HistoryRequest& r) {
  const tlm::TmDesc* d = find_packet(r.packet);
  if (d == nullptr || !plottable(*d))
    return Error::make(Errc::invalid_argument, "history: packet '%s' unknown", r.packet.c_str());
  auto archive = open_archive(archive_path, r.start_ms, r.end_ms);
  if (!archive) return archive.error();
  ground::ArchiveQuery q;
  q.apid = d->apid;
  q.from_s = r.start_ms / 1000.0;
  q.to_s = r.end_ms / 1000.0;
  q.min_severity = r.min_severity;
  q.limit = r.limit;
  std::string out = "[";
  bool first = true, unknown_field = false;
  auto s = (*archive)->query(q, [&](const ground::ArchivedPacket& a) {
    auto p = tlm::decode_tm(a.raw);
    if (!p) return;
    const std::string t = time_ms(a.scet_s);
    if (r.field.empty()) {
      out += std::string(first ? "" : ",") + "{\"t\":" + t + ",\"packet\":" + a.decoded +
             ",\"names\":" + packet_names_json(*p) +
             ",\"line\":" + json_string(ground::format_line(*p)) + "}";
    } else {
      double v = 0;
      if (!field_value(*p, r.field, v)) {
        unknown_field = true;
        return;
      }
      out += std::string(first ? "" : ",") + "{\"t\":" + t + ",\"v\":" + sample_number(v) + "}";
    }
    first = false;
  });
  if (!s) return s.error();
  if (unknown_field)
    return Error::make(Errc::invalid_argument, "history: %s has no field '%s'", d->name,
                       r.field.c_str());
  return out + "]";
}

Result<std::string> gaps_json(const std::string& archive_path, double start_ms, double end_ms) {
  auto archive = open_archive(archive_path, start_ms, end_ms);
  if (!archive) return archive.error();
  ground::ArchiveQuery q;
  q.from_s = start_ms / 1000.0;
  q.to_s = end_ms / 1000.0;
  ground::SeqTracker seqs;
  std::string out = "[";
  auto s = (*archive)->query(q, [&](const ground::ArchivedPacket& a) {
    auto p = tlm::decode_tm(a.raw);
    if (!p) return;
    const std::uint32_t missing = seqs.observe(*p);
    if (missing == 0) return;
    out += std::string(out.size() > 1 ? "," : "") + "{\"t\":" + time_ms(a.scet_s) +
           ",\"packet\":" + json_string(a.packet) + ",\"apid\":" + std::to_string(a.apid) +
           ",\"seq\":" + std::to_string(a.seq) + ",\"missing\":" + std::to_string(missing) + "}";
  });
  if (!s) return s.error();
  return out + "]";
}

}  // namespace petra::gnd

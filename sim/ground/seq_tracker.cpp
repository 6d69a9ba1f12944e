#include "sim/ground/seq_tracker.hpp"

#include <sstream>
#include <variant>

namespace petra::ground {

namespace {

// A step forward of at most half the count space is a loss; a longer one is
// the count going backwards (a restarted service starts again at 0).
constexpr std::uint32_t kSeqModulo = wire::kSeqCountMask + 1u;

const char* apid_name(std::uint16_t apid) {
  const tlm::TmDesc* d = tlm::find_telemetry(apid);
  return d != nullptr ? d->name : "?";
}

}  // namespace

std::uint32_t SeqTracker::observe(const tlm::TmPacket& p) {
  if (const auto* hk = std::get_if<tlm::Housekeeping>(&p.body)) flight_dropped_ = hk->tlm_dropped;
  const std::uint16_t seq = p.header.primary.seq_count;
  auto [it, first] = apids_.try_emplace(p.header.primary.apid);
  ApidStats& s = it->second;
  ++s.received;
  std::uint32_t missing = 0;
  if (!first) {
    const std::uint32_t step = (seq + kSeqModulo - s.last_seq) % kSeqModulo;
    if (step == 0 || step > kSeqModulo / 2) {
      ++s.restarts;
    } else if (step > 1) {
      missing = step - 1;
      s.missing += missing;
      ++s.gaps;
    }
  }
  s.last_seq = seq;
  return missing;
}

std::uint64_t SeqTracker::missing() const {
  std::uint64_t n = 0;
  for (const auto& [apid, s] : apids_) n += s.missing;
  return n;
}

std::string SeqTracker::summary_line() const {
  std::uint64_t packets = 0, gaps = 0;
  std::ostringstream per_apid;
  for (const auto& [apid, s] : apids_) {
    packets += s.received;
    gaps += s.gaps;
    if (s.missing > 0)
      per_apid << (per_apid.tellp() > 0 ? ", " : "") << apid_name(apid) << " " << s.missing;
  }
  std::ostringstream o;
  o << "summary: " << packets << " packets, " << missing() << " missing in " << gaps << " gaps";
  if (per_apid.tellp() > 0) o << " (" << per_apid.str() << ")";
  o << ", " << bad_ << " bad, flight dropped ";
  if (flight_dropped_ < 0)
    o << "? (no housekeeping)";
  else
    o << flight_dropped_;
  return o.str();
}

std::string SeqTracker::summary_json() const {
  std::uint64_t packets = 0;
  std::ostringstream list;
  for (const auto& [apid, s] : apids_) {
    packets += s.received;
    list << (list.tellp() > 0 ? "," : "") << "{\"apid\":" << apid << ",\"packet\":\""
         << apid_name(apid) << "\",\"received\":" << s.received << ",\"missing\":" << s.missing
         << ",\"gaps\":" << s.gaps << ",\"restarts\":" << s.restarts << "}";
  }
  std::ostringstream o;
  o << "{\"summary\":{\"packets\":" << packets << ",\"missing\":" << missing()
    << ",\"bad\":" << bad_ << ",\"flight_dropped\":";
  if (flight_dropped_ < 0)
    o << "null";
  else
    o << flight_dropped_;
  o << ",\"apids\":[" << list.str() << "]}}";
  return o.str();
}

}  // namespace petra::ground

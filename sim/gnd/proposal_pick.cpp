#include "sim/gnd/proposal_pick.hpp"

#include <sstream>
#include <vector>

#include "algo/arm/kinematics.hpp"
#include "algo/core/json_reader.hpp"
#include "algo/surface/grind_planes.hpp"
#include "sim/gnd/json_text.hpp"
#include "sim/ground/proposals_format.hpp"

namespace petra::gnd {

namespace {

int listed(const tlm::Proposals& list) {
  return list.count < PETRA_MAX_PROPOSALS ? list.count : PETRA_MAX_PROPOSALS;
}

// The number member `key` of the object, or an error naming it.
Result<double> number_member(const json::Document& doc, const char* key) {
  const std::uint32_t i = doc.find(0, key);
  if (i == 0) return Error::make(Errc::missing_field, "%s: missing", key);
  if (doc.token(i).type != json::Type::number)
    return Error::make(Errc::wrong_type, "%s: must be a number", key);
  return doc.token(i).number;
}

Result<PickAs> pick_as(const json::Document& doc) {
  const std::uint32_t i = doc.find(0, "as");
  if (i == 0) return PickAs::SELECT_PROPOSAL;
  const std::string_view as = doc.text_of(i);
  if (doc.token(i).type == json::Type::string && as == "select_proposal")
    return PickAs::SELECT_PROPOSAL;
  if (doc.token(i).type == json::Type::string && as == "select_roi") return PickAs::SELECT_ROI;
  return Error::make(Errc::invalid_argument, "as: \"select_proposal\" or \"select_roi\"");
}

}  // namespace

std::optional<int> proposal_at(const tlm::Proposals& list, double u, double v) {
  for (int i = 0; i < listed(list); ++i) {  // best rank first
    const auto k = static_cast<std::size_t>(i);
    const double x = list.roi_px[4 * k], y = list.roi_px[4 * k + 1];
    const double w = list.roi_px[4 * k + 2], h = list.roi_px[4 * k + 3];
    if (u >= x && u < x + w && v >= y && v < y + h) return i + 1;
  }
  return std::nullopt;
}

Result<cmd::Command> pick_command(const tlm::Proposals& list, int rank, PickAs as) {
  if (rank < 1 || rank > listed(list))
    return Error::make(Errc::out_of_range, "rank: %d is not listed (proposals %u has %d)", rank,
                       list.proposal_id, listed(list));
  const auto i = static_cast<std::size_t>(rank - 1);
  if (as == PickAs::SELECT_PROPOSAL) {
    cmd::SelectProposalArgs a;
    a.proposal_id = list.proposal_id;
    a.rank = static_cast<std::uint8_t>(rank);
    return cmd::Command{cmd::FunctionCode::SELECT_PROPOSAL, 0, a};
  }
  cmd::SelectRoiArgs a;
  a.x_px = list.roi_px[4 * i];
  a.y_px = list.roi_px[4 * i + 1];
  a.w_px = list.roi_px[4 * i + 2];
  a.h_px = list.roi_px[4 * i + 3];
  a.planes = list.planes_c[i];
  a.has_click = 1;
  a.click_u_px = list.click_px[2 * i];
  a.click_v_px = list.click_px[2 * i + 1];
  if (a.out_of_range() >= 0)  // e.g. c = 0: the proposer ran no chain on it
    return Error::make(Errc::invalid_argument,
                       "rank: proposal %d's ROI, click or c (%u) is not a SELECT_ROI", rank,
                       a.planes);
  return cmd::Command{cmd::FunctionCode::SELECT_ROI, 0, a};
}

Result<cmd::Command> parse_pick_request(std::string_view body, const tlm::Proposals* list) {
  if (list == nullptr)
    return Error::make(Errc::not_ready, "proposals: none received yet (send PROPOSE)");
  std::vector<json::Token> tokens(32);
  auto doc = json::Document::parse(body, tokens);
  if (!doc) return Error::make(Errc::parse_error, "request: not JSON: %s", doc.error().message);
  if (doc->token(0).type != json::Type::object)
    return Error::make(Errc::invalid_argument, "request: must be a JSON object");
  auto as = pick_as(*doc);
  if (!as) return as.error();
  if (doc->find(0, "rank") != 0) {
    auto rank = number_member(*doc, "rank");
    if (!rank) return rank.error();
    return pick_command(*list, static_cast<int>(*rank), *as);
  }
  auto u = number_member(*doc, "u");
  if (!u) return u.error();
  auto v = number_member(*doc, "v");
  if (!v) return v.error();
  const std::optional<int> rank = proposal_at(*list, *u, *v);
  if (!rank)
    return Error::make(Errc::out_of_range, "u, v: (%.0f, %.0f) is on no proposal of list %u", *u,
                       *v, list->proposal_id);
  return pick_command(*list, *rank, *as);
}

std::string proposals_names_json(const tlm::Proposals& list) {
  std::ostringstream o;
  o << "{\"empty_reason\":" << json_string(ground::proposal_empty_name(list.empty_reason));
  auto array = [&](const char* name, auto&& key) {
    o << ",\"" << name << "\":[";
    for (int i = 0; i < listed(list); ++i)
      o << (i ? "," : "") << json_string(key(static_cast<std::size_t>(i)));
    o << "]";
  };
  array("notes", [&](std::size_t i) { return ground::proposal_note_key(list.note[i]); });
  array("verdicts",
        [&](std::size_t i) { return verdict_key(static_cast<PlaneVerdict>(list.verdict[i])); });
  array("reaches", [&](std::size_t i) {
    return arm::arm_reason_name(static_cast<arm::ArmReason>(list.reach[i]));
  });
  o << "}";
  return o.str();
}

}  // namespace petra::gnd

// The HTTP side of the ground station (cpp-httplib): serves the page and
// bridges it to the GroundStation.
//   GET  /                      static page (web dir); /vendor/ npm-built assets
//   GET  /api/info              command definitions (names, fields, ranges, units)
//   GET  /api/palette           the picture colours (algo/chain/palette.hpp), see palette_json()
//   GET  /api/dictionary        every telemetry point (telemetry_history.hpp, for Open MCT)
//   GET  /api/history?packet=P[&field=F]&start=MS&end=MS[&min_severity=N]
//                               a point's or a packet kind's history from the archive
//   GET  /api/gaps?start=MS&end=MS  the archive's sequence gaps per APID
//   GET  /api/events            server-sent events (see ground_station.hpp)
//   POST /api/command           {"command": NAME, "args": {...}} -> {"counter": n}
//                               or HTTP 400 {"error": "<field>: <problem>"}
//   POST /api/proposals/pick    {"u":U,"v":V} or {"rank":K} [,"as":"select_roi"]: sends
//                               SELECT_PROPOSAL (or SELECT_ROI) for the proposal of the
//                               last PROPOSALS at that point (proposal_pick.hpp)
//                               -> {"command":..,"counter":n} or HTTP 400 naming the member
//   GET  /api/arm               the arm's geometry, limits and stowed skeleton
//   POST /api/arm/plan          {"centroid_mm":[..],"normal":[..],"standoff_mm":S}
//                               -> the approach from the current joints, or the
//                               refusal and its reason (arm_model.hpp)
//   GET  /api/product/<kind>    latest left_image | disparity | overlay | point_cloud | proposals,
//                               raw bytes; X-Petra-Width/Height/Format/Id headers
#pragma once

#include <memory>
#include <string>

#include "algo/core/result.hpp"
#include "sim/gnd/ground_station.hpp"

namespace petra::gnd {

struct ServerOptions {
  std::string bind = "127.0.0.1";
  int port = 8080;  // 0: pick a free port
  std::string web_dir;
  std::string vendor_dir;  // may be missing: the page then runs without its 3D view
};

class HttpServer {
 public:
  explicit HttpServer(GroundStation& station);
  ~HttpServer();
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  // Binds; returns the port actually bound.
  Result<int> bind(const ServerOptions& options);
  // Serves until stop() (from another thread or a signal watcher).
  void run();
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The body of GET /api/info.
std::string info_json();
// The body of GET /api/palette: algo/chain/palette.hpp as "#rrggbb" strings
// {"planes":[..8..],"ground","rock","shadow","rejected","no_data","disparity_ramp":[..5..]}.
std::string palette_json();

}  // namespace petra::gnd

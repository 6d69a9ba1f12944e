#include "sim/gnd/http_server.hpp"

#include <arpa/inet.h>
#include <httplib.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <vector>

#include "algo/chain/palette.hpp"
#include "cmd/commands.hpp"
#include "sim/gnd/command_request.hpp"
#include "sim/gnd/json_text.hpp"
#include "sim/gnd/proposal_pick.hpp"
#include "sim/gnd/telemetry_history.hpp"

namespace petra::gnd {

namespace {

std::uint8_t product_kind(const std::string& name) {
  for (std::uint8_t k = 1; k <= 5; ++k)
    if (name == ground::product_name(k)) return k;
  return 0;
}

void answer_error(httplib::Response& res, int status, const std::string& message) {
  res.status = status;
  res.set_content(json_error(message), "application/json");
}

const char* mime_type(const std::filesystem::path& file) {
  const std::string ext = file.extension().string();
  if (ext == ".html") return "text/html";
  if (ext == ".js") return "text/javascript";
  if (ext == ".css") return "text/css";
  if (ext == ".png") return "image/png";
  if (ext == ".json") return "application/json";
  return "application/octet-stream";
}

// Static files under `root`: no "..", no hidden files, regular files only.
// Sent through a content provider so the library does not compress them on
// the fly (brotli at its default quality takes seconds on three.js).
void serve_file(const std::string& root, const std::string& rel, httplib::Response& res) {
  namespace fs = std::filesystem;
  const fs::path relative =
      rel.empty() || rel.back() == '/' ? fs::path(rel) / "index.html" : fs::path(rel);
  for (const auto& part : relative)
    if (part == ".." || part.string().starts_with("."))
      return answer_error(res, 400, "path: '" + rel + "' is not allowed");
  const fs::path file = fs::path(root) / relative;
  std::error_code ec;
  const auto size = fs::file_size(file, ec);
  if (ec || !fs::is_regular_file(file))
    return answer_error(res, 404, "path: no file '" + rel + "'");
  auto in = std::make_shared<std::ifstream>(file, std::ios::binary);
  res.set_header("Cache-Control", "no-cache");
  res.set_content_provider(static_cast<std::size_t>(size), mime_type(file),
                           [in](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
                             std::vector<char> buf(std::min<std::size_t>(length, 1 << 16));
                             in->seekg(static_cast<std::streamoff>(offset));
                             in->read(buf.data(), static_cast<std::streamsize>(buf.size()));
                             const auto got = static_cast<std::size_t>(in->gcount());
                             return got > 0 && sink.write(buf.data(), got);
                           });
}

}  // namespace

std::string info_json() {
  std::ostringstream o;
  o << "{\"commands\":[";
  bool first = true;
  for (const cmd::CommandDesc& c : cmd::command_table()) {
    o << (first ? "" : ",") << "{\"name\":" << json_string(c.name)
      << ",\"code\":" << unsigned{c.code} << ",\"description\":" << json_string(c.description)
      << ",\"fields\":[";
    first = false;
    bool first_field = true;
    for (const auto& f : c.fields) {
      o << (first_field ? "" : ",") << "{\"name\":" << json_string(f.name) << ",\"min\":" << f.min
        << ",\"max\":" << f.max << ",\"unit\":" << json_string(f.unit) << "}";
      first_field = false;
    }
    o << "]}";
  }
  o << "]}";
  return o.str();
}

std::string palette_json() {
  auto rgb = [](palette::Rgb8 c) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "\"#%02x%02x%02x\"", c.r, c.g, c.b);
    return std::string(buf);
  };
  std::ostringstream o;
  o << "{\"planes\":[";
  for (int k = 0; k < palette::kPlaneCount; ++k) o << (k ? "," : "") << rgb(palette::kPlanes[k]);
  o << "],\"ground\":" << rgb(palette::kGround) << ",\"rock\":" << rgb(palette::kRock)
    << ",\"shadow\":" << rgb(palette::kShadow) << ",\"rejected\":" << rgb(palette::kRejected)
    << ",\"no_data\":" << rgb(palette::kNoData) << ",\"disparity_ramp\":[";
  for (int k = 0; k < palette::kRampStops; ++k)
    o << (k ? "," : "") << rgb(palette::kDisparityRamp[k]);
  o << "]}";
  return o.str();
}

struct HttpServer::Impl {
  explicit Impl(GroundStation& s) : station(s) {}
  GroundStation& station;
  httplib::Server server;

  // Signs and sends a command the request made: {"command":..,"counter":n},
  // HTTP 400 naming the request's problem, or 503 when it could not be sent.
  void send_and_answer(const Result<cmd::Command>& command, httplib::Response& res) {
    if (!command) return answer_error(res, 400, command.error().message);
    auto counter = station.send(*command);
    if (!counter) return answer_error(res, 503, counter.error().message);
    const cmd::CommandDesc* d = cmd::find_command(static_cast<std::uint8_t>(command->code));
    res.set_content(
        "{\"command\":" + json_string(d->name) + ",\"counter\":" + std::to_string(*counter) + "}",
        "application/json");
  }

  void routes(const ServerOptions& options) {
    // One thread per connected page (its event stream) plus the requests.
    server.new_task_queue = [] { return new httplib::ThreadPool(16); };
    server.set_payload_max_length(kMaxRequestBytes);
    const std::string web = options.web_dir, vendor = options.vendor_dir;
    server.Get(R"(/vendor/(.*))", [vendor](const httplib::Request& req, httplib::Response& res) {
      serve_file(vendor, req.matches[1], res);
    });
    server.Get(R"(/((?!api/).*))", [web](const httplib::Request& req, httplib::Response& res) {
      serve_file(web, req.matches[1], res);
    });

    server.Get("/api/info", [](const httplib::Request&, httplib::Response& res) {
      res.set_content(info_json(), "application/json");
    });
    server.Get("/api/dictionary", [](const httplib::Request&, httplib::Response& res) {
      res.set_content(dictionary_json(), "application/json");
    });
    server.Get("/api/history", [this](const httplib::Request& req, httplib::Response& res) {
      HistoryRequest r;
      r.packet = req.get_param_value("packet");
      r.field = req.get_param_value("field");
      r.start_ms = std::strtod(req.get_param_value("start").c_str(), nullptr);
      r.end_ms = std::strtod(req.get_param_value("end").c_str(), nullptr);
      if (req.has_param("min_severity"))
        r.min_severity = std::atoi(req.get_param_value("min_severity").c_str());
      auto body = history_json(station.archive_path(), r);
      if (!body) return answer_error(res, 400, body.error().message);
      res.set_content(*body, "application/json");
    });
    server.Get("/api/gaps", [this](const httplib::Request& req, httplib::Response& res) {
      auto body = gaps_json(station.archive_path(),
                            std::strtod(req.get_param_value("start").c_str(), nullptr),
                            std::strtod(req.get_param_value("end").c_str(), nullptr));
      if (!body) return answer_error(res, 400, body.error().message);
      res.set_content(*body, "application/json");
    });
    server.Get("/api/palette", [](const httplib::Request&, httplib::Response& res) {
      res.set_content(palette_json(), "application/json");
    });

    server.Post("/api/command", [this](const httplib::Request& req, httplib::Response& res) {
      send_and_answer(parse_command_request(req.body), res);
    });

    server.Post("/api/proposals/pick", [this](const httplib::Request& req, httplib::Response& res) {
      const std::optional<tlm::Proposals> list = station.last_proposals();
      send_and_answer(parse_pick_request(req.body, list ? &*list : nullptr), res);
    });

    server.Get("/api/arm", [this](const httplib::Request&, httplib::Response& res) {
      res.set_content(station.arm_model().geometry_json(), "application/json");
    });

    server.Post("/api/arm/plan", [this](const httplib::Request& req, httplib::Response& res) {
      auto plan = station.arm_model().plan_json(req.body, station.arm_joints_deg());
      if (!plan) return answer_error(res, 400, plan.error().message);
      res.set_content(*plan, "application/json");
    });

    server.Get(R"(/api/product/([a-z_]+))", [this](const httplib::Request& req,
                                                   httplib::Response& res) {
      const std::uint8_t kind = product_kind(req.matches[1]);
      if (kind == 0)
        return answer_error(res, 400,
                            "product: '" + std::string(req.matches[1]) +
                                "' is not left_image, disparity, overlay, "
                                "point_cloud or proposals");
      auto p = station.product(kind);
      if (!p) return answer_error(res, 404, "product: none received yet");
      res.set_header("Cache-Control", "no-store");
      res.set_header("X-Petra-Width", std::to_string(p->width));
      res.set_header("X-Petra-Height", std::to_string(p->height));
      res.set_header("X-Petra-Format", std::to_string(p->format));
      res.set_header("X-Petra-Id", std::to_string(p->id));
      res.set_content(std::string(p->bytes.begin(), p->bytes.end()), "application/octet-stream");
    });

    server.Get("/api/events", [this](const httplib::Request& req, httplib::Response& res) {
      // A reconnecting EventSource resumes after the last message it saw.
      auto last = std::make_shared<std::uint64_t>(0);
      if (req.has_header("Last-Event-ID"))
        *last = std::strtoull(req.get_header_value("Last-Event-ID").c_str(), nullptr, 10);
      res.set_header("Cache-Control", "no-store");
      res.set_chunked_content_provider(
          "text/event-stream", [this, last](std::size_t, httplib::DataSink& sink) {
            if (station.hub().closed()) return false;
            const auto messages = station.hub().wait_after(*last, 500);
            std::string out;
            for (const auto& m : messages) {
              out += "id: " + std::to_string(m.seq) + "\nevent: " + m.event + "\ndata: " + m.json +
                     "\n\n";
              *last = m.seq;
            }
            if (out.empty()) out = ": idle\n\n";  // notices a closed page
            return sink.is_writable() && sink.write(out.data(), out.size());
          });
    });

    server.set_exception_handler(
        [](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
          answer_error(res, 500, "internal error");
        });
  }
};

HttpServer::HttpServer(GroundStation& station) : impl_(std::make_unique<Impl>(station)) {}
HttpServer::~HttpServer() {
  stop();
}

Result<int> HttpServer::bind(const ServerOptions& options) {
  in_addr addr{};
  if (inet_pton(AF_INET, options.bind.c_str(), &addr) != 1)
    return Error::make(Errc::invalid_argument, "--bind '%s': not a numeric IPv4 address",
                       options.bind.c_str());
  if (options.port < 0 || options.port > 65535)
    return Error::make(Errc::out_of_range, "--port %d: outside 0..65535", options.port);
  if (!std::filesystem::is_regular_file(std::filesystem::path(options.web_dir) / "index.html"))
    return Error::make(Errc::missing_field, "--web '%s': no index.html there",
                       options.web_dir.c_str());
  impl_->routes(options);
  if (options.port == 0) {
    const int port = impl_->server.bind_to_any_port(options.bind.c_str());
    if (port <= 0) return Error::make(Errc::io_error, "cannot bind %s:0", options.bind.c_str());
    return port;
  }
  if (!impl_->server.bind_to_port(options.bind.c_str(), options.port))
    return Error::make(Errc::io_error, "cannot bind %s:%d (in use?)", options.bind.c_str(),
                       options.port);
  return options.port;
}

void HttpServer::run() {
  impl_->server.listen_after_bind();
}

void HttpServer::stop() {
  if (impl_) impl_->server.stop();
}

}  // namespace petra::gnd

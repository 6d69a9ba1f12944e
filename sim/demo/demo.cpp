#include "sim/demo/demo.hpp"

#include <signal.h>
#include <sodium.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <thread>
#include <vector>

#include "algo/core/json_reader.hpp"
#include "cmd/command_packet.hpp"
#include "cmd/param_defs.hpp"
#include "hal/udp_link.hpp"
#include "sim/demo/demo_report.hpp"
#include "sim/ground/key_file.hpp"
#include "sim/ground/product_assembler.hpp"
#include "sim/ground/tlm_format.hpp"
#include "sim/io/image_io.hpp"
#include "tlm/event_defs.hpp"

namespace petra::demo {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct Scene {
  fs::path left, right, calib, truth;
  Rect roi;
  int planes = 2;
  bool has_click = false;
  int click_u = 0, click_v = 0;
};

std::string read_all(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

std::optional<fs::path> find_image(const fs::path& dir, const std::string& stem) {
  for (const char* ext : {".png", ".pgm", ".ppm"})
    if (fs::exists(dir / (stem + ext))) return dir / (stem + ext);
  return std::nullopt;
}

Result<Scene> load_scene(const fs::path& dir) {
  Scene s;
  auto l = find_image(dir, "left");
  auto r = find_image(dir, "right");
  if (!l || !r)
    return Error::make(Errc::missing_field,
                       "scene %s: needs left and right images (.png/.pgm/.ppm)", dir.c_str());
  s.left = *l;
  s.right = *r;
  if (fs::exists(dir / "calib.json")) s.calib = dir / "calib.json";
  s.truth = dir / "truth.json";
  const std::string truth = read_all(s.truth);
  if (truth.empty())
    return Error::make(Errc::missing_field, "scene %s: truth.json with roi and planes needed",
                       dir.c_str());
  std::vector<json::Token> tokens(4096);
  auto doc = json::Document::parse(truth, tokens);
  if (!doc) return Error::make(Errc::parse_error, "truth.json: %s", doc.error().message);
  const std::uint32_t roi = doc->find(0, "roi");
  if (roi == 0 || doc->token(roi).count != 4)
    return Error::make(Errc::missing_field, "truth.json: roi [x,y,w,h] missing");
  int v[4];
  for (std::uint32_t i = 0; i < 4; ++i)
    v[i] = static_cast<int>(doc->token(doc->element(roi, i)).number);
  s.roi = Rect{v[0], v[1], v[2], v[3]};
  if (const std::uint32_t c = doc->find(0, "planes");
      c != 0 && doc->token(c).type == json::Type::number)
    s.planes = static_cast<int>(doc->token(c).number);
  if (const std::uint32_t k = doc->find(0, "click"); k != 0 && doc->token(k).count == 2) {
    s.has_click = true;
    s.click_u = static_cast<int>(doc->token(doc->element(k, 0)).number);
    s.click_v = static_cast<int>(doc->token(doc->element(k, 1)).number);
  }
  return s;
}

std::string find_fsw(const Options& o) {
  if (!o.fsw_binary.empty()) return o.fsw_binary;
  const fs::path self = fs::canonical("/proc/self/exe");
  for (const fs::path& p :
       {self.parent_path().parent_path() / "fsw" / "petra-fsw", self.parent_path() / "petra-fsw"})
    if (fs::exists(p)) return p.string();
  return "petra-fsw";
}

std::uint16_t free_port() {
  hal::UdpLink l;
  if (!l.open("127.0.0.1", 0)) return 0;
  return l.local_port();
}

class Session {
 public:
  ~Session() { stop(); }
  bool start(const std::string& fsw, const fs::path& config, const fs::path& log) {
    pid_ = fork();
    if (pid_ == 0) {
      const std::string cmd =
          "exec '" + fsw + "' --config '" + config.string() + "' 2>'" + log.string() + "'";
      execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    return pid_ > 0;
  }
  bool alive() { return pid_ > 0 && waitpid(pid_, nullptr, WNOHANG) == 0; }
  void stop() {
    if (pid_ <= 0) return;
    kill(pid_, SIGTERM);
    waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }

 private:
  pid_t pid_ = -1;
};

// A received image product as PNG (what an operator opens); "" for clouds.
std::string write_png_of(const ground::Product& p, const fs::path& dir) {
  if (p.format != 1 && p.format != 2) return "";
  const std::string path =
      (dir / (std::string(ground::product_name(p.kind)) + "_" + std::to_string(p.id) + ".png"))
          .string();
  if (p.format == 1) {
    if (!io::write_png(path, ConstGray8View(p.bytes.data(), p.width, p.height))) return "";
  } else {
    io::RgbImage img(p.width, p.height);
    std::copy(p.bytes.begin(), p.bytes.end(), img.rgb.begin());
    if (!io::write_png(path, img)) return "";
  }
  return path;
}

std::string quote(const std::string& s) {
  return "'" + s + "'";
}

// petra-fsw's points budget, from the memory table it prints at boot (the
// "points" column of its one row), so `petra eval` runs on the same budget;
// "" when the log has no such table.
std::string flight_points_budget(const std::string& fsw_log) {
  auto trim = [](std::string c) {
    c.erase(0, std::min(c.size(), c.find_first_not_of(' ')));
    c.erase(c.find_last_not_of(' ') + 1);
    return c;
  };
  std::istringstream lines(fsw_log);
  std::ptrdiff_t column = -1;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("| ", 0) != 0) continue;  // table rows only, not the |---| rule
    std::vector<std::string> cells;
    std::istringstream row(line.substr(1));
    for (std::string cell; std::getline(row, cell, '|');) cells.push_back(trim(cell));
    if (column < 0) {  // the header row
      const auto at = std::find(cells.begin(), cells.end(), "points");
      if (at != cells.end()) column = at - cells.begin();
      continue;
    }
    const std::string& v = cells[static_cast<std::size_t>(
        std::min<std::ptrdiff_t>(column, static_cast<std::ptrdiff_t>(cells.size()) - 1))];
    return !v.empty() && v.find_first_not_of("0123456789") == std::string::npos ? v : "";
  }
  return "";
}

// `petra eval` on the same pair, when this build has it: its planes.json and
// pictures in dir/eval. Returns its planes.json text, or "" (with a line why).
std::string run_petra_eval(const Options& o, const Scene& scene, const fs::path& dir,
                           double shadow_fraction, std::FILE* out) {
  if (std::system((quote(o.self_binary) + " eval --help >/dev/null 2>&1").c_str()) != 0) {
    std::fprintf(out,
                 "   (`petra eval` is not in this build: no ground-side run to compare with)\n");
    return "";
  }
  const fs::path eval_dir = dir / "eval";
  char roi[80], click[40] = "";
  std::snprintf(roi, sizeof roi, "%d,%d,%d,%d", scene.roi.x, scene.roi.y, scene.roi.w, scene.roi.h);
  if (scene.has_click)
    std::snprintf(click, sizeof click, " --click %d,%d", scene.click_u, scene.click_v);
  char sf[32];
  std::snprintf(sf, sizeof sf, "%.17g", shadow_fraction);
  const std::string points = flight_points_budget(read_all(dir / "fsw.log"));
  const std::string cmd =
      quote(o.self_binary) + " eval --calib " + quote(scene.calib.string()) + " --left " +
      quote((dir / "pairs/left.pgm").string()) + " --right " +
      quote((dir / "pairs/right.pgm").string()) + " --roi " + roi + " --planes " +
      std::to_string(scene.planes) + click + " --shadow-fraction " + sf +
      (points.empty() ? "" : " --points " + points) + " --out " + quote(eval_dir.string()) + " > " +
      quote((dir / "eval.txt").string()) + " 2>&1";
  if (std::system(cmd.c_str()) != 0) {
    std::fprintf(out, "   `petra eval` on the same pair failed: %s\n",
                 read_all(dir / "eval.txt").c_str());
    return "";
  }
  return read_all(eval_dir / "planes.json");
}

// Why the demo stops, or nothing while it goes on.
using Stop = std::optional<std::string>;

// 1. The scene folder: the one given, or one the simulator writes in dir.
Stop find_scene(const Options& o, const fs::path& dir, std::FILE* out, fs::path& scene_dir) {
  scene_dir = o.scene_dir;
  if (!scene_dir.empty()) {
    std::fprintf(out, "1. scene: %s\n", scene_dir.c_str());
    return std::nullopt;
  }
  scene_dir = dir / "scene";
  const std::string sim = "'" + o.self_binary + "' sim scene --seed " + std::to_string(o.seed) +
                          " --out '" + scene_dir.string() + "' >/dev/null 2>&1";
  if (std::system(sim.c_str()) != 0)
    return "no scene: the scene simulator (`petra sim scene`) is not in this build; give a scene "
           "folder with --scene DIR (left.png, right.png, calib.json, truth.json)";
  std::fprintf(out, "1. scene: simulated with seed %d in %s\n", o.seed, scene_dir.c_str());
  return std::nullopt;
}

// The pair where petra-fsw's file camera reads it (dir/pairs); the left
// image stays for the ROI picture and the budget.
Stop write_camera_pair(const Scene& scene, const fs::path& dir, io::GrayImage& left_out) {
  auto left = io::read_gray_image(scene.left.string());
  auto right = io::read_gray_image(scene.right.string());
  if (!left) return left.error().message;
  if (!right) return right.error().message;
  if (auto s = io::write_pgm((dir / "pairs/left.pgm").string(), left->view()); !s)
    return std::string("cannot write the camera folder: ") + s.error().message;
  if (auto s = io::write_pgm((dir / "pairs/right.pgm").string(), right->view()); !s)
    return std::string("cannot write the camera folder: ") + s.error().message;
  left_out = std::move(*left);
  return std::nullopt;
}

// What the operator selected, drawn on the left image (best effort).
void write_roi_picture(const io::GrayImage& left, Rect r, const fs::path& dir, std::FILE* out) {
  io::RgbImage pic(left.width, left.height);
  for (int y = 0; y < left.height; ++y)
    for (int x = 0; x < left.width; ++x) {
      const std::uint8_t g = left.view()(x, y);
      std::uint8_t* px = pic.at(x, y);
      px[0] = px[1] = px[2] = g;
      const bool edge = (x >= r.x - 1 && x <= r.x + r.w && (y == r.y - 1 || y == r.y + r.h)) ||
                        (y >= r.y - 1 && y <= r.y + r.h && (x == r.x - 1 || x == r.x + r.w));
      if (edge) px[0] = 255, px[1] = 200, px[2] = 0;
    }
  if (io::write_png((dir / "roi.png").string(), pic))
    std::fprintf(out, "   the operator's ROI on the left image: %s\n", (dir / "roi.png").c_str());
}

// petra-fsw's configuration: loopback links, a budget of the image's size
// and a file camera reading dir/pairs.
Stop write_fsw_config(const fs::path& dir, std::uint16_t cmd_port, std::uint16_t tlm_port,
                      const io::GrayImage& left, const Scene& scene) {
  std::ostringstream cfg;
  cfg << R"({"uplink":{"host":"127.0.0.1","port":)" << cmd_port
      << R"(,"key_file":"petra.key"},"downlink":{"host":"127.0.0.1","port":)" << tlm_port
      << R"(},"budget":{"image_width":)" << left.width << R"(,"image_height":)" << left.height
      << R"(},"camera":{"kind":"file","dir":"pairs"})";  // the flight default budget
  if (!scene.calib.empty()) cfg << R"(,"calib":")" << scene.calib.string() << "\"";
  cfg << "}\n";
  if (auto s = io::write_text_file((dir / "fsw.json").string(), cfg.str()); !s)
    return s.error().message;
  return std::nullopt;
}

// Signed telecommands to petra-fsw, each with the next counter.
struct Uplink {
  hal::UdpLink link;
  cmd::AuthKey key;
  std::uint32_t counter = 0;

  std::uint32_t send(cmd::Command c) {
    c.counter = ++counter;
    std::vector<std::uint8_t> p(cmd::kMaxCommandBytes);
    auto n = cmd::encode_command_packet(c, static_cast<std::uint16_t>(counter), key, p);
    if (n) link.send(std::span(p).first(*n));
    return c.counter;
  }
};

// What petra-fsw sends back, gathered as it arrives; products are written
// to dir as they complete.
struct Downlink {
  hal::UdpLink link;
  fs::path dir;
  std::FILE* out = nullptr;
  ground::ProductAssembler assembler;
  std::vector<tlm::GrindPlane> planes;
  std::optional<tlm::EvalResult> result;
  std::optional<tlm::GroundPlane> ground_plane;
  std::map<std::uint32_t, tlm::Ack> final_ack;
  std::vector<std::string> pictures;
  std::vector<ground::Product> products;
  bool booted = false;
  std::vector<std::uint8_t> buf = std::vector<std::uint8_t>(4096);

  // Receives for `ms` milliseconds.
  void pump(int ms) {
    const auto until = Clock::now() + std::chrono::milliseconds(ms);
    while (Clock::now() < until) {
      auto n = link.receive_wait(buf, 20);
      if (!n || !n->got) continue;
      auto p = tlm::decode_tm(std::span(buf).first(std::min(n->size, buf.size())));
      if (p) take(*p);
    }
  }

  void take(const tlm::TmPacket& p) {
    if (const auto* e = std::get_if<tlm::Event>(&p.body)) {
      if (e->event_id == static_cast<std::uint16_t>(EventId::BOOT_COMPLETE)) booted = true;
      if (e->event_id != static_cast<std::uint16_t>(EventId::PRODUCT_SENT))
        std::fprintf(out, "   event: %s\n", ground::event_text(*e).c_str());
    } else if (const auto* a = std::get_if<tlm::Ack>(&p.body)) {
      if (a->stage != static_cast<std::uint8_t>(AckStage::ACCEPTED)) final_ack[a->counter] = *a;
    } else if (const auto* g = std::get_if<tlm::GrindPlane>(&p.body)) {
      planes.push_back(*g);
    } else if (const auto* r = std::get_if<tlm::EvalResult>(&p.body)) {
      result = *r;
    } else if (const auto* gp = std::get_if<tlm::GroundPlane>(&p.body)) {
      ground_plane = *gp;
    } else if (const auto* c = std::get_if<tlm::Product>(&p.body)) {
      // Written after the wait (write_pictures): a PNG encoded here held
      // the loop for up to 0.7 s while the next products' chunks streamed in.
      if (auto done = assembler.add(*c)) products.push_back(std::move(*done));
    }
  }

  // The products received, as files in dir (and a PNG of each picture).
  void write_pictures() {
    for (const ground::Product& p : products) {
      pictures.push_back(ground::write_product(p, dir.string()));
      const std::string png = write_png_of(p, dir);
      if (!png.empty()) pictures.push_back(png);
    }
  }

  bool has_product(std::uint8_t kind) const {
    return std::any_of(products.begin(), products.end(),
                       [&](const ground::Product& p) { return p.kind == kind; });
  }

  // True when the command's final acknowledgement came and is not COMPLETED.
  bool refused(std::uint32_t counter) const {
    const auto a = final_ack.find(counter);
    return a != final_ack.end() &&
           a->second.stage != static_cast<std::uint8_t>(AckStage::COMPLETED);
  }
};

cmd::SelectRoiArgs select_roi_args(const Scene& scene) {
  cmd::SelectRoiArgs sel;
  sel.x_px = static_cast<std::uint16_t>(scene.roi.x);
  sel.y_px = static_cast<std::uint16_t>(scene.roi.y);
  sel.w_px = static_cast<std::uint16_t>(scene.roi.w);
  sel.h_px = static_cast<std::uint16_t>(scene.roi.h);
  sel.planes = static_cast<std::uint8_t>(scene.planes);
  sel.has_click = scene.has_click ? 1 : 0;
  sel.click_u_px = static_cast<std::uint16_t>(scene.click_u);
  sel.click_v_px = static_cast<std::uint16_t>(scene.click_v);
  return sel;
}

// Why EVALUATE did not complete, with a hint where the reason alone is
// not enough.
std::string evaluate_failure(const tlm::Ack& ack) {
  const Reason why = static_cast<Reason>(ack.reason);
  return std::string("EVALUATE ") + ack_stage_name(static_cast<AckStage>(ack.stage)) + ": " +
         reason_name(why) +
         (why == Reason::NO_PIPELINE      ? " (this build has no evaluation pipeline)"
          : why == Reason::PIPELINE_ERROR ? " (the EVAL_FAILED event above says why)"
                                          : "");
}

// 3-4. The operator's commands, then the wait for EVALUATE's outcome and the
// pictures that follow the planes.
Stop evaluate(const Scene& scene, int timeout_s, Session& fsw, Uplink& up, Downlink& down,
              std::FILE* out) {
  // Full-resolution pictures first (the flight default sends thumbnails).
  const std::uint32_t thumb_counter =
      up.send({cmd::FunctionCode::SET_PARAM, 0,
               cmd::SetParamArgs{static_cast<std::uint16_t>(ParamId::THUMB_DECIMATION), 1.0}});
  std::fprintf(out, "3. sent SELECT_ROI x %d, y %d, %d x %d px, c = %d (signed, counter %u)\n",
               scene.roi.x, scene.roi.y, scene.roi.w, scene.roi.h, scene.planes, up.counter + 1);
  const std::uint32_t sel_counter =
      up.send({cmd::FunctionCode::SELECT_ROI, 0, select_roi_args(scene)});
  const std::uint32_t eval_counter =
      up.send({cmd::FunctionCode::EVALUATE, 0, cmd::EvaluateArgs{1}});
  std::fprintf(out, "4. sent EVALUATE (take a new pair first); waiting for the grind planes...\n");
  const auto deadline = Clock::now() + std::chrono::seconds(timeout_s);
  while (!down.final_ack.count(eval_counter) && Clock::now() < deadline && fsw.alive())
    down.pump(200);
  if (down.refused(thumb_counter))
    std::fprintf(out, "   (SET_PARAM THUMB_DECIMATION 1 refused: the pictures are thumbnails)\n");
  if (down.refused(sel_counter))
    return std::string("SELECT_ROI refused: ") +
           reason_name(static_cast<Reason>(down.final_ack.at(sel_counter).reason));
  if (!down.final_ack.count(eval_counter))
    return "no answer to EVALUATE within " + std::to_string(timeout_s) + " s";
  if (down.refused(eval_counter)) return evaluate_failure(down.final_ack.at(eval_counter));
  // The products follow the planes: wait for the disparity and the overlay.
  const bool expect_pictures = down.result && down.result->dense_points > 0;
  for (int i = 0; i < 150 && expect_pictures && !(down.has_product(2) && down.has_product(3)); ++i)
    down.pump(200);
  down.pump(300);
  if (down.link.kernel_drops() > 0 || down.assembler.incomplete() > 0)
    std::fprintf(
        out,
        "   telemetry: %u packets dropped by this end's receive buffer; not complete when "
        "the wait ended (lost chunks, or still streaming): %s\n",
        down.link.kernel_drops(),
        down.assembler.incomplete() > 0 ? down.assembler.incomplete_text().c_str() : "none");
  return std::nullopt;
}

// 8. Where the operator finds the pictures and files.
void list_outputs(const fs::path& dir, const std::vector<std::string>& pictures, bool have_eval,
                  std::FILE* out) {
  std::fprintf(out, "8. look at these in %s:\n", dir.c_str());
  std::fprintf(out, "   roi.png            the operator's ROI on the left image\n");
  for (const auto& p : pictures)
    if (p.ends_with(".png"))
      std::fprintf(out, "   %-18s received as telemetry\n", fs::path(p).filename().c_str());
  std::fprintf(out, "   planes.json        the grind planes received (contract format)\n");
  if (have_eval)
    std::fprintf(
        out,
        "   eval/              petra eval's planes.json, overlay.png, disparity.png, cloud.ply\n");
}

// 1. The scene, its pair in petra-fsw's camera folder and the operator's
// ROI drawn on the left image (kept in `left` for the budget).
Stop stage_scene(const Options& o, const fs::path& dir, std::FILE* out, Scene& scene,
                 io::GrayImage& left) {
  fs::path scene_dir;
  if (Stop s = find_scene(o, dir, out, scene_dir)) return s;
  auto loaded = load_scene(scene_dir);
  if (!loaded) return loaded.error().message;
  scene = *loaded;
  if (scene.calib.empty())
    std::fprintf(
        out, "   (no calib.json in the scene: petra-fsw will have no rig to reconstruct with)\n");
  if (Stop s = write_camera_pair(scene, dir, left)) return s;
  write_roi_picture(left, scene.roi, dir, out);
  return std::nullopt;
}

// 2. Key, configuration, petra-fsw, links; returns once it has booted.
Stop start_fsw(const Options& o, const fs::path& dir, const Scene& scene, const io::GrayImage& left,
               Session& fsw, Uplink& up, Downlink& down, std::FILE* out) {
  if (sodium_init() < 0) return "libsodium failed to initialise";
  randombytes_buf(up.key.bytes.data(), up.key.bytes.size());
  // Mode 0600, with its flight counter beside it (petra-fsw refuses a key without one).
  if (auto k = ground::write_new_key((dir / "petra.key").string(), up.key, true); !k)
    return k.error().message;
  const std::uint16_t cmd_port = free_port();
  const std::uint16_t tlm_port = free_port();
  if (!down.link.open("127.0.0.1", tlm_port)) return "cannot listen for telemetry";
  down.link.set_receive_buffer(8 << 20);  // products arrive in bursts of chunks (as sim/gnd)
  if (Stop s = write_fsw_config(dir, cmd_port, tlm_port, left, scene)) return s;
  const std::string fsw_bin = find_fsw(o);
  if (!fsw.start(fsw_bin, dir / "fsw.json", dir / "fsw.log")) return "cannot start " + fsw_bin;
  std::fprintf(out, "2. petra-fsw started (%s): commands on udp %u, telemetry on udp %u, log %s\n",
               fsw_bin.c_str(), cmd_port, tlm_port, (dir / "fsw.log").c_str());
  if (!up.link.open("127.0.0.1", 0) || !up.link.set_peer("127.0.0.1", cmd_port))
    return "cannot open the uplink";
  // Boot builds the tables and touches the whole arena: seconds in a Debug
  // build on a loaded machine, more under emulation (HIL bench). Wait while the process lives,
  // within the limit.
  const auto boot_deadline = Clock::now() + std::chrono::seconds(o.timeout_s);
  while (!down.booted && fsw.alive() && Clock::now() < boot_deadline) down.pump(100);
  if (!down.booted)
    return std::string("petra-fsw did not boot (") +
           (fsw.alive() ? "no BOOT_COMPLETE within the time limit" : "it exited") + "); see " +
           (dir / "fsw.log").string() + ": " + read_all(dir / "fsw.log");
  return std::nullopt;
}

// 5-8. What came back as telemetry, the same pair through `petra eval` on
// the ground, the score against the scene's truth, and where to look.
Stop report(const Options& o, const Scene& scene, const fs::path& dir, const Downlink& down,
            std::FILE* out) {
  const auto& result = down.result;
  Received got{result, down.ground_plane, down.planes};
  std::fprintf(out, "5. evaluation %u: %u of %u grind planes received as telemetry in %u ms\n",
               result ? result->eval_id : 0, result ? result->planes_found : 0,
               result ? result->planes_requested : 0, result ? result->total_ms : 0);
  print_received(got, out);
  const std::string tlm_json = planes_json(got);
  if (auto s = io::write_text_file((dir / "planes.json").string(), tlm_json); !s)
    return s.error().message;

  // 6. With the same parameters (the demo leaves them as they are).
  std::fprintf(out, "6. the same pair through `petra eval` on the ground:\n");
  const std::string eval_json =
      scene.calib.empty()
          ? std::string()
          : run_petra_eval(o, scene, dir, param_default(ParamId::SHADOW_FRACTION), out);
  if (!eval_json.empty())
    std::fprintf(out, "   %s\n",
                 same_planes(eval_json, tlm_json)
                     ? "identical grind planes (eval/planes.json equals planes.json from telemetry)"
                     : "DIFFERENT grind planes: compare eval/planes.json with planes.json");

  // 7. The verdict is printed; the exit status says only whether planes came back.
  std::fprintf(out, "7. score against %s (petra score):\n", scene.truth.c_str());
  (void)score_and_print(read_all(scene.truth), tlm_json, DemoLimits{}, out);

  list_outputs(dir, down.pictures, !eval_json.empty(), out);
  return std::nullopt;
}

}  // namespace

int run(const Options& o, std::FILE* out) {
  auto fail = [out](const std::string& why) {
    std::fprintf(out, "demo stopped: %s\n", why.c_str());
    std::fflush(out);
    if (out != stderr) std::fprintf(stderr, "petra demo: %s\n", why.c_str());
    return 1;
  };
  std::error_code ec;
  const fs::path dir = fs::absolute(o.out_dir, ec);
  if (ec) return fail(o.out_dir + ": " + ec.message());
  if (fs::create_directories(dir / "pairs", ec); ec)
    return fail("cannot create the output folder " + (dir / "pairs").string() + ": " +
                ec.message());
  Scene scene;
  io::GrayImage left;
  if (Stop s = stage_scene(o, dir, out, scene, left)) return fail(*s);
  Uplink up;
  Downlink down;
  down.dir = dir;
  down.out = out;
  Session fsw;  // declared last: stopped first
  if (Stop s = start_fsw(o, dir, scene, left, fsw, up, down, out)) return fail(*s);
  const Stop evaluated = evaluate(scene, o.timeout_s, fsw, up, down, out);
  down.write_pictures();  // what came, also when EVALUATE failed
  if (evaluated) return fail(*evaluated);
  if (Stop s = report(o, scene, dir, down, out)) return fail(*s);
  fsw.stop();
  return down.planes.empty() ? 1 : 0;
}

}  // namespace petra::demo

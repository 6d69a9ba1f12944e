// `petra gnd serve`: the operator's ground station in a browser. Serves the
// page on loopback (by default), signs and sends its commands to petra-fsw,
// and streams the decoded telemetry back to it (sim/gnd, docs/ops.md).
#include <signal.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>

#include "sim/cli/commands.hpp"
#include "sim/gnd/ground_station.hpp"
#include "sim/gnd/http_server.hpp"

#ifndef PETRA_GND_WEB_DIR
#define PETRA_GND_WEB_DIR "sim/gnd/web"
#endif
#ifndef PETRA_GND_VENDOR_DIR
#define PETRA_GND_VENDOR_DIR ""
#endif

namespace petra::cli {

// The 3D view's modules in the vendor folder (sim/gnd/web/index.html's import map).
constexpr const char* kViewAssets[] = {"three/build/three.module.js", "delaunator/index.js"};

void add_gnd(CLI::App& app, Outcome& outcome) {
  auto* gnd = app.add_subcommand("gnd", "Ground station in the browser");
  gnd->require_subcommand(1);
  auto* sub =
      gnd->add_subcommand("serve", "Serve the ground station page and bridge it to petra-fsw");
  static gnd::ServerOptions http{.bind = "127.0.0.1",
                                 .port = 8080,
                                 .web_dir = PETRA_GND_WEB_DIR,
                                 .vendor_dir = PETRA_GND_VENDOR_DIR};
  static gnd::StationOptions link;
  sub->add_option("--port", http.port, "HTTP port (0: any free port)")->capture_default_str();
  sub->add_option("--bind", http.bind, "HTTP address (numeric IPv4; loopback unless you mean it)")
      ->capture_default_str();
  sub->add_option("--web", http.web_dir, "folder of the page")->capture_default_str();
  sub->add_option("--vendor", http.vendor_dir, "folder of the npm-built assets (three.js)")
      ->capture_default_str();
  sub->add_option("--key", link.key_path, "uplink key file (64 hex digits)")->capture_default_str();
  sub->add_option("--counter-file", link.counter_path, "last counter used (default: KEY.counter)");
  sub->add_option("--host", link.fsw_host, "petra-fsw command address")->capture_default_str();
  sub->add_option("--cmd-port", link.cmd_port, "petra-fsw command port")->capture_default_str();
  sub->add_option("--tlm-host", link.tlm_host, "local address receiving telemetry")
      ->capture_default_str();
  sub->add_option("--tlm-port", link.tlm_port, "telemetry port")->capture_default_str();
  sub->add_option("--left-image", link.left_image,
                  "image shown until the first LEFT_IMAGE product (e.g. the scene's left.png)");
  sub->add_option("--archive", link.archive_path,
                  "telemetry archive (SQLite file, created when absent): every packet received "
                  "is kept there (petra archive)");
  static std::string arm_mount = "300,100,100,90";
  sub->add_option("--arm-mount", arm_mount,
                  "arm base in the world, x_mm,y_mm,z_mm,yaw_deg (petra-fsw's arm.mount)")
      ->capture_default_str();
  sub->callback([&outcome] {
    auto geometry = gnd::parse_arm_mount(arm_mount);
    if (!geometry) {
      outcome.exit_code = fail("gnd serve", geometry.error().message);
      return;
    }
    link.arm_geometry = *geometry;
    // The page works without its npm assets, minus the 3D view: say so, and how to get them.
    for (const char* asset : kViewAssets)
      if (!std::filesystem::exists(std::filesystem::path(http.vendor_dir) / asset)) {
        std::fprintf(stderr,
                     "petra gnd serve: warning: no 3D view: %s/%s is missing (install the page's "
                     "assets: cmake --build <this build folder> --target gnd_web, or --vendor "
                     "DIR)\n",
                     http.vendor_dir.c_str(), asset);
        break;
      }
    // SIGINT/SIGTERM are taken by a watcher thread that stops the server, so
    // the telemetry thread and the sockets close cleanly.
    sigset_t stop_signals;
    sigemptyset(&stop_signals);
    sigaddset(&stop_signals, SIGINT);
    sigaddset(&stop_signals, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

    gnd::GroundStation station;
    if (auto s = station.start(link); !s) {
      outcome.exit_code = fail("gnd serve", s.error().message);
      return;
    }
    gnd::HttpServer server(station);
    auto port = server.bind(http);
    if (!port) {
      outcome.exit_code = fail("gnd serve", port.error().message);
      return;
    }
    std::printf("petra gnd: serving http://%s:%d/ (commands to %s:%d, telemetry on %s:%d)\n",
                http.bind.c_str(), *port, link.fsw_host.c_str(), link.cmd_port,
                link.tlm_host.c_str(), link.tlm_port);
    std::fflush(stdout);
    std::thread watcher([&] {
      int sig = 0;
      sigwait(&stop_signals, &sig);
      station.hub().close();
      server.stop();
    });
    server.run();
    // run() also returns when the socket fails: wake the watcher.
    pthread_kill(watcher.native_handle(), SIGTERM);
    watcher.join();
    station.stop();
    std::printf("petra gnd: stopped (%llu packets, %llu bad)\n",
                static_cast<unsigned long long>(station.packets()),
                static_cast<unsigned long long>(station.bad_packets()));
  });
}

}  // namespace petra::cli

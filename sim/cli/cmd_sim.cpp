// `petra sim scene --seed N --out DIR [options]`: renders one synthetic stereo
// scene with its ground truth (docs/scene.md).
// `petra sim set --out DIR`: renders the standard set into DIR/scene_KK.
#include <chrono>
#include <cstdio>
#include <exception>
#include <optional>
#include <string>

#include "sim/cli/commands.hpp"
#include "sim/scene/scene_render.hpp"
#include "sim/scene/scene_set.hpp"

namespace petra::cli {

namespace {

struct SceneArgs {
  std::optional<long long> seed;  // signed, so a negative seed is reported, not wrapped
  std::optional<int> set_index;
  std::string out;
  std::optional<std::string> boundary;
  std::optional<std::string> shape;
  std::optional<int> flat_faces;
  std::optional<double> sun_elevation, sun_azimuth, rock_size, rock_distance, camera_height;
  std::optional<double> noise;
  bool no_texture = false;
  std::optional<int> edge_supersampling;
  // The realistic world (docs/scene.md): --real sets every knob's realistic default.
  bool real = false;
  bool multi = false;  // --set-index K of the multi-rock set
  std::optional<double> relief, pebbles, stones, slope, slope_azimuth, face_roughness,
      face_curvature, gain_left, gain_right, offset_left, offset_right, vignetting, prnu,
      calib_residual, burial;
  std::optional<int> neighbours;
  std::optional<int> rocks;
  bool roi_fill = false;
};

void add_world_options(CLI::App* cmd, SceneArgs& a) {
  cmd->add_flag("--real", a.real,
                "realistic world: every knob below at its realistic default (else 0 / gain 1)");
  cmd->add_option("--relief", a.relief, "terrain relief RMS, mm, 0..10 (real 2)");
  cmd->add_option("--pebbles", a.pebbles, "share of the ground under pebbles, 0..0.25 (real 0.12)");
  cmd->add_option("--stones", a.stones, "small stones per m^2 near the rock, 0..200 (real 25)");
  cmd->add_option("--slope", a.slope, "ground slope under the rock, deg, 0..20 (real 6)");
  cmd->add_option("--slope-azimuth", a.slope_azimuth,
                  "uphill direction from the heading, counter-clockwise, deg (default: drawn)");
  cmd->add_option("--face-roughness", a.face_roughness,
                  "rock faces' relief RMS, mm, 0..2 (real 0.3)");
  cmd->add_option("--face-curvature", a.face_curvature, "rock faces' bulge, 1/m, 0..5 (real 0.5)");
  cmd->add_option("--gain-left", a.gain_left, "left camera gain, 0.5..1.5 (real 1)");
  cmd->add_option("--gain-right", a.gain_right, "right camera gain, 0.5..1.5 (real 0.92)");
  cmd->add_option("--offset-left", a.offset_left, "left camera offset, DN, -40..40 (real 0)");
  cmd->add_option("--offset-right", a.offset_right, "right camera offset, DN, -40..40 (real 4)");
  cmd->add_option("--vignetting", a.vignetting, "fall-off at the corners, 0..0.6 (real 0.2)");
  cmd->add_option("--prnu", a.prnu, "pixel response non-uniformity, 0..0.05 (real 0.01)");
  cmd->add_option("--calib-residual", a.calib_residual,
                  "calib.json's RMS reprojection error against the true rig, px, 0..2 (real 0.3)");
  cmd->add_option(
      "--burial", a.burial,
      "share of the rock's height below the ground, 0.15..0.7 (default: drawn 0.15..0.35)");
}

void apply_world(const SceneArgs& a, sim::World& w) {
  auto set = [](const std::optional<double>& v, double& field) {
    if (v) field = *v;
  };
  set(a.relief, w.relief_rms_mm);
  set(a.pebbles, w.pebble_cover);
  set(a.stones, w.stones_per_m2);
  set(a.slope, w.slope_deg);
  if (a.slope_azimuth) w.slope_azimuth_deg = *a.slope_azimuth;
  set(a.face_roughness, w.face_roughness_mm);
  set(a.face_curvature, w.face_curvature_per_m);
  set(a.gain_left, w.gain_left);
  set(a.gain_right, w.gain_right);
  set(a.offset_left, w.offset_left_dn);
  set(a.offset_right, w.offset_right_dn);
  set(a.vignetting, w.vignetting);
  set(a.prnu, w.prnu);
  set(a.calib_residual, w.calib_residual_px);
  if (a.burial) w.burial = *a.burial;
}

void add_scene_options(CLI::App* cmd, SceneArgs& a) {
  cmd->add_option("--boundary", a.boundary, "clear | weak (default: drawn from the seed)");
  cmd->add_option("--shape", a.shape, "blocky | rounded | slab (default: drawn)");
  cmd->add_option("--flat-faces", a.flat_faces,
                  "number of large flat faces, 2 or 3 (default: drawn)");
  cmd->add_option("--sun-elevation", a.sun_elevation,
                  "sun elevation, deg, 10..80 (default: drawn)");
  cmd->add_option("--sun-azimuth", a.sun_azimuth,
                  "sun azimuth from the rig-to-rock heading, counter-clockwise from above, deg; "
                  "180 = behind the cameras (default: drawn, 100..145 either side)");
  cmd->add_option("--rock-size", a.rock_size,
                  "largest rock dimension, mm, 80..250 (default: drawn)");
  cmd->add_option("--rock-distance", a.rock_distance,
                  "rig to rock centre, mm, 500..900 (default: drawn)");
  cmd->add_option("--camera-height", a.camera_height,
                  "rig above the ground, mm, 400..700 (default: drawn)");
  cmd->add_option("--noise", a.noise, "sensor noise at 128 DN, DN, 0..20 (default 1.5)");
  cmd->add_flag("--no-texture", a.no_texture, "uniform albedo (for geometry checks)");
  cmd->add_option("--edge-supersampling", a.edge_supersampling,
                  "samples per axis in edge pixels, 2..16 (default 8)");
  add_world_options(cmd, a);
  cmd->add_option("--neighbours", a.neighbours,
                  "further rocks touching the rock, beside or behind it, 0..3 (default 0)");
  cmd->add_option("--rocks", a.rocks,
                  "full rocks in view, 2..6, some not grindable or not reachable by design "
                  "(default: the one rock)");
  cmd->add_flag("--roi-fill", a.roi_fill,
                "truth ROI inside the rock's silhouette: no ground in it (default: rock, "
                "shadow and a margin of ground)");
}

// Options as given on the command line over a base (seed or set entry).
Result<sim::SceneOptions> to_options(const SceneArgs& a, sim::SceneOptions o) {
  if (a.boundary) {
    auto b = sim::parse_boundary(*a.boundary);
    if (!b) return b.error();
    o.boundary = *b;
  }
  if (a.shape) {
    auto s = sim::parse_shape(*a.shape);
    if (!s) return s.error();
    o.shape = *s;
  }
  if (a.flat_faces) o.flat_faces = *a.flat_faces;
  if (a.sun_elevation) o.sun_elevation_deg = *a.sun_elevation;
  if (a.sun_azimuth) o.sun_azimuth_deg = *a.sun_azimuth;
  if (a.rock_size) o.rock_size_mm = *a.rock_size;
  if (a.rock_distance) o.rock_distance_mm = *a.rock_distance;
  if (a.camera_height) o.camera_height_mm = *a.camera_height;
  if (a.noise) o.noise_sigma_dn = *a.noise;
  if (a.no_texture) o.texture = false;
  if (a.edge_supersampling) o.edge_supersampling = *a.edge_supersampling;
  apply_world(a, o.world);
  if (a.neighbours) o.neighbours = *a.neighbours;
  if (a.roi_fill) o.roi_fill = true;
  if (a.rocks) o.rocks = *a.rocks;
  PETRA_TRY(sim::validate(o));
  return o;
}

// Renders and writes one scene; prints a one-line summary.
Status render_and_write(const sim::SceneOptions& o, const std::string& dir) {
  PETRA_TRY(sim::prepare_output_dir(dir));  // fail before the slow part
  const auto t0 = std::chrono::steady_clock::now();
  auto p = sim::render_scene(o);
  if (!p) return p.error();
  PETRA_TRY(sim::write_scene(*p, dir));
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const sim::Scene& s = p->scene;
  const Rect& r = p->truth.roi;
  std::printf(
      "seed %llu: %s boundary, %s rock %.0f mm at %.0f mm, %d flat faces, sun %.0f deg; "
      "roi %d,%d,%d,%d; disparity %.1f..%.1f px; %s (%.2f s)\n",
      static_cast<unsigned long long>(o.seed), sim::boundary_name(s.boundary),
      sim::shape_name(s.shape), s.rock_size_mm, s.rock_distance_mm, s.flat_faces,
      s.sun_elevation_deg, r.x, r.y, r.w, r.h, p->truth.disparity_min, p->truth.disparity_max,
      dir.c_str(), secs);
  if (!s.neighbour_kind.empty()) {
    std::printf("  rocks:");
    for (const auto kind : s.neighbour_kind) std::printf(" %s", sim::rock_kind_name(kind));
    std::printf("\n");
  }
  return {};
}

}  // namespace

void add_sim(CLI::App& app, Outcome& outcome) {
  auto* sim_cmd = app.add_subcommand("sim", "Synthetic scenes with ground truth");
  sim_cmd->require_subcommand(1);

  static SceneArgs scene_args;
  auto* scene = sim_cmd->add_subcommand("scene", "Render one stereo scene and its ground truth");
  auto* seed_opt = scene->add_option("--seed", scene_args.seed, "scene seed, 0..2^53-1");
  auto* index_opt = scene->add_option("--set-index", scene_args.set_index,
                                      "render entry K of the standard set (0.." +
                                          std::to_string(sim::kStandardSetSize - 1) +
                                          "), or with --real of the realistic set, with "
                                          "--multi of the multi-rock set");
  scene->add_flag("--multi", scene_args.multi, "--set-index K is of the multi-rock set");
  seed_opt->excludes(index_opt);
  scene->add_option("--out", scene_args.out, "output directory (created)")->required();
  add_scene_options(scene, scene_args);
  scene->callback([&outcome] {
    try {
      sim::SceneOptions base;
      if (scene_args.set_index) {
        const int k = *scene_args.set_index;
        const int size = scene_args.multi  ? sim::kMultiSetSize
                         : scene_args.real ? sim::kRealSetSize
                                           : sim::kStandardSetSize;
        if (k < 0 || k >= size) {
          const std::string msg =
              "--set-index " + std::to_string(k) + " outside 0.." + std::to_string(size - 1);
          outcome.exit_code = fail("sim scene", msg.c_str());
          return;
        }
        const auto entries = scene_args.multi  ? sim::multi_rock_scene_set()
                             : scene_args.real ? sim::real_scene_set()
                                               : sim::standard_scene_set();
        base = entries[static_cast<std::size_t>(k)];
      } else if (scene_args.seed) {
        const long long seed = *scene_args.seed;
        if (seed < 0 || static_cast<unsigned long long>(seed) > sim::kMaxSeed) {
          const std::string msg =
              "--seed " + std::to_string(seed) + " outside 0.." + std::to_string(sim::kMaxSeed);
          outcome.exit_code = fail("sim scene", msg.c_str());
          return;
        }
        base.seed = static_cast<std::uint64_t>(seed);
        if (scene_args.real) base.world = sim::realistic_world();
      } else {
        outcome.exit_code = fail("sim scene", "--seed N or --set-index K is required");
        return;
      }
      auto o = to_options(scene_args, base);
      if (!o) {
        outcome.exit_code = fail("sim scene", o.error().message);
        return;
      }
      auto st = render_and_write(*o, scene_args.out);
      if (!st) outcome.exit_code = fail("sim scene", st.error().message);
    } catch (const std::exception& e) {
      outcome.exit_code = fail("sim scene", e.what());
    }
  });

  static std::string set_out;
  static bool set_real = false;
  static bool set_multi = false;
  auto* set = sim_cmd->add_subcommand("set", "Render the standard scene set into DIR/scene_KK");
  set->add_option("--out", set_out, "output directory (created)")->required();
  set->add_flag("--real", set_real,
                "the realistic set (" + std::to_string(sim::kRealSetSize) +
                    " scenes, docs/scene.md) instead of the clean one");
  set->add_flag("--multi", set_multi,
                "the multi-rock set (" + std::to_string(sim::kMultiSetSize) +
                    " realistic scenes of 3..6 rocks, docs/scene.md \"Several rocks\")");
  set->callback([&outcome] {
    try {
      const auto entries = set_multi  ? sim::multi_rock_scene_set()
                           : set_real ? sim::real_scene_set()
                                      : sim::standard_scene_set();
      for (std::size_t k = 0; k < entries.size(); ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "/scene_%02zu", k);
        auto st = render_and_write(entries[k], set_out + name);
        if (!st) {
          outcome.exit_code = fail("sim set", st.error().message);
          return;
        }
      }
    } catch (const std::exception& e) {
      outcome.exit_code = fail("sim set", e.what());
    }
  });
  // `petra sim arm`: the arm's simulated drives (`petra sim-arm` is the same command).
  add_arm_sim(*sim_cmd, outcome, "arm");
}

}  // namespace petra::cli

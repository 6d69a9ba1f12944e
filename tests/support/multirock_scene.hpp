// The multi-rock scene the tests share (seed 7, 3 rocks, clean world: a
// grindable rock, a second one and a too small one; about 4 s of one core),
// rendered once per build tree into the test cache and read from there by
// every test process that uses it (tests/support/cached_dir.hpp).
#pragma once

#include <filesystem>

#include "sim/scene/scene_render.hpp"
#include "tests/support/cached_dir.hpp"

namespace petra::test {

inline sim::SceneOptions multirock_options() {
  sim::SceneOptions o;
  o.seed = 7;
  o.rocks = 3;
  return o;
}

// The directory `petra sim scene --seed 7 --rocks 3` writes; empty on failure.
inline const std::filesystem::path& multirock_scene_dir() {
  static const std::filesystem::path dir =
      cached_dir("multirock_seed7", "sim scene --seed 7 --rocks 3", this_executable(),
                 [](const std::filesystem::path& out) {
                   auto p = sim::render_scene(multirock_options());
                   return p && sim::write_scene(*p, out.string()).ok();
                 });
  return dir;
}

}  // namespace petra::test

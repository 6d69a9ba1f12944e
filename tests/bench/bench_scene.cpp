// Scene simulator speed (docs/scene.md, "Speed"): the whole
// scene as `petra sim scene` renders it, and its parts, on one core.
#include <benchmark/benchmark.h>

#include "sim/scene/scene_render.hpp"
#include "sim/scene/scene_set.hpp"

namespace {

using namespace petra::sim;

SceneOptions entry(std::int64_t k) {
  return standard_scene_set()[static_cast<std::size_t>(k)];
}

void BM_MakeScene(benchmark::State& state) {
  const SceneOptions o = entry(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(make_scene(o).ok());
}

void BM_RenderLeftView(benchmark::State& state) {
  auto scene = make_scene(entry(state.range(0)));
  if (!scene) {
    state.SkipWithError(scene.error().message);
    return;
  }
  for (auto _ : state) benchmark::DoNotOptimize(render_view(*scene, Eye::left).edge_pixels);
}

void BM_RectifiedTruth(benchmark::State& state) {
  auto scene = make_scene(entry(state.range(0)));
  if (!scene) {
    state.SkipWithError(scene.error().message);
    return;
  }
  for (auto _ : state) benchmark::DoNotOptimize(render_rectified_truth(*scene).ok());
}

// Everything `petra sim scene` computes (files not written).
void render_each_time(benchmark::State& state, const SceneOptions& o) {
  for (auto _ : state) benchmark::DoNotOptimize(render_scene(o).ok());
}

void BM_RenderScene(benchmark::State& state) {
  render_each_time(state, entry(state.range(0)));
}

// The realistic world (rough terrain and faces: the ray marches dominate).
void BM_RenderRealScene(benchmark::State& state) {
  render_each_time(state, real_scene_set()[static_cast<std::size_t>(state.range(0))]);
}

// Several rough rocks in view.
void BM_RenderMultiRockScene(benchmark::State& state) {
  render_each_time(state, multi_rock_scene_set()[static_cast<std::size_t>(state.range(0))]);
}

BENCHMARK(BM_MakeScene)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RenderLeftView)->Arg(0)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_RectifiedTruth)->Arg(0)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_RenderScene)->DenseRange(0, 3)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_RenderRealScene)->Arg(0)->Arg(17)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_RenderMultiRockScene)->Arg(0)->Arg(3)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();

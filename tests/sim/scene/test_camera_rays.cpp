// The renderer's ray generator is algo's pixel_to_ray, bit for bit.
#include "sim/scene/camera_rays.hpp"

#include <gtest/gtest.h>

#include "sim/scene/scene.hpp"

namespace petra::sim {
namespace {

TEST(CameraRays, IdenticalToPixelToRay) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    SceneOptions o;
    o.seed = seed;
    auto s = make_scene(o);
    ASSERT_TRUE(s.ok());
    for (const TsaiCamera* cam : {&s->rig.left, &s->rig.right}) {
      const CameraRays rays(*cam);
      for (double v = -0.5; v <= 767.5; v += 7.25)
        for (double u = -0.5; u <= 1023.5; u += 9.125) {
          const Ray r = pixel_to_ray(*cam, {u, v});
          EXPECT_EQ(rays.origin(), r.origin_mm);
          const Eigen::Vector3d d = rays.direction(u, v);
          ASSERT_EQ(d, r.direction) << "pixel " << u << ", " << v;
        }
    }
  }
}

}  // namespace
}  // namespace petra::sim

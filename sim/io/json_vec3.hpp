// A 3-vector as a JSON array [x, y, z]: the ground files' one way of writing
// normals, centroids and points.
#pragma once

#include <Eigen/Core>

#include "algo/core/json_writer.hpp"

namespace petra::sim {

inline void write_vec3(json::Writer& w, const Eigen::Vector3d& v) {
  w.begin_array().number(v.x()).number(v.y()).number(v.z()).end_array();
}

}  // namespace petra::sim

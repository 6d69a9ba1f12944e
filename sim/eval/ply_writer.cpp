#include "sim/eval/ply_writer.hpp"

#include <cstring>

#include "algo/chain/products.hpp"
#include "sim/io/image_io.hpp"

namespace petra::eval {

namespace {

void put(std::string& out, const void* p, std::size_t n) {
  out.append(static_cast<const char*>(p), n);
}

}  // namespace

std::string ply_bytes(const ReconstructionOutput& r, ConstGray8View left, bool with_faces) {
  const std::size_t n = r.xyz_mm.size();
  std::string out = "ply\nformat binary_little_endian 1.0\n";
  out += "comment Petra reconstruction: world frame of calib.json, mm\n";
  out += "comment colour: class (ground, rock, grind plane 1..c); gray: left image intensity\n";
  out += "element vertex " + std::to_string(n) + "\n";
  out += "property float x\nproperty float y\nproperty float z\n";
  out += "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar gray\n";
  if (with_faces) {
    out += "element face " + std::to_string(r.mesh.size()) + "\n";
    out += "property list uchar int vertex_indices\n";
  }
  out += "end_header\n";
  out.reserve(out.size() + n * 16 + (with_faces ? r.mesh.size() * 13 : 0));
  for (std::size_t i = 0; i < n; ++i) {
    const float xyz[3] = {static_cast<float>(r.xyz_mm[i].x()), static_cast<float>(r.xyz_mm[i].y()),
                          static_cast<float>(r.xyz_mm[i].z())};
    put(out, xyz, sizeof xyz);  // x86-64 and aarch64 are little-endian
    const palette::Rgb8 c = products::class_colour(r.vertex_class[i]);  // the one palette
    const int u = r.pixels[i].u, v = r.pixels[i].v;
    const std::uint8_t rgbg[4] = {c.r, c.g, c.b,
                                  left.in_bounds(u, v) ? left(u, v) : std::uint8_t{0}};
    put(out, rgbg, sizeof rgbg);
  }
  if (with_faces) {
    for (const MeshTriangle& t : r.mesh) {
      const std::uint8_t three = 3;
      put(out, &three, 1);
      // PLY faces are counter-clockwise seen from outside; our triangles are
      // positively oriented in image coordinates (y down), i.e. clockwise as
      // seen by the camera: swap two vertices so normals face the camera.
      const std::int32_t idx[3] = {t.v[0], t.v[2], t.v[1]};
      put(out, idx, sizeof idx);
    }
  }
  return out;
}

Status write_ply(const std::string& path, const ReconstructionOutput& r, ConstGray8View left,
                 bool with_faces) {
  const std::string bytes = ply_bytes(r, left, with_faces);
  return io::write_binary_file(path, bytes.data(), bytes.size());
}

}  // namespace petra::eval

#include "sim/scene/scene_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace petra::sim {

bool faces_point(const RockFace& face, const Eigen::Vector3d& centre) {
  return face.plane.normal.dot(centre) > face.plane.offset_mm;
}

std::vector<VisibleFacet> visible_facets(const Scene& scene) {
  return visible_facets(scene, scene.rock);
}

std::vector<VisibleFacet> visible_facets(const Scene& scene, const ConvexRock& rock) {
  const Eigen::Vector3d cl = camera_centre_world(scene.rig.left);
  const Eigen::Vector3d cr = camera_centre_world(scene.rig.right);
  std::vector<VisibleFacet> out;
  for (std::size_t i = 0; i < rock.faces.size(); ++i) {
    const RockFace& f = rock.faces[i];
    if (!faces_point(f, cl) || !faces_point(f, cr)) continue;
    VisibleFacet v;
    v.polygon = exposed_polygon(f);
    v.area_mm2 = polygon_area(v.polygon);
    if (v.area_mm2 < kMinFacetAreaMm2) continue;
    v.face = static_cast<int>(i);
    v.normal = f.plane.normal;
    v.centroid = polygon_centroid(v.polygon);
    v.grind_face = f.plane.grind_face;
    out.push_back(std::move(v));
  }
  std::stable_sort(out.begin(), out.end(), [](const VisibleFacet& a, const VisibleFacet& b) {
    return a.area_mm2 > b.area_mm2;
  });
  return out;
}

std::vector<Eigen::Vector3d> polygon_edge_points(const Polygon3& poly, int per_edge) {
  std::vector<Eigen::Vector3d> pts;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector3d& a = poly[i];
    const Eigen::Vector3d& b = poly[(i + 1) % poly.size()];
    for (int k = 0; k < per_edge; ++k)
      pts.push_back(a + (b - a) * (static_cast<double>(k) / per_edge));
  }
  return pts;
}

std::vector<Eigen::Vector3d> rock_outline_points(const ConvexRock& rock, int per_edge) {
  std::vector<Eigen::Vector3d> pts;
  for (const auto& f : rock.faces) {
    const auto e = polygon_edge_points(exposed_polygon(f), per_edge);
    pts.insert(pts.end(), e.begin(), e.end());
  }
  return pts;
}

namespace {

double cross2(const Eigen::Vector3d& o, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// Andrew's monotone chain on (x, y); counter-clockwise.
Polygon3 convex_hull_xy(std::vector<Eigen::Vector3d> pts) {
  std::sort(pts.begin(), pts.end(), [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (pts.size() < 3) return pts;
  Polygon3 hull(2 * pts.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross2(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross2(hull[k - 2], hull[k - 1], pts[i - 1]) <= 0) --k;
    hull[k++] = pts[i - 1];
  }
  hull.resize(k - 1);
  return hull;
}

}  // namespace

Polygon3 shadow_region(const ConvexRock& rock, const Eigen::Vector3d& sun) {
  std::vector<Eigen::Vector3d> pts;
  for (const auto& f : rock.faces)
    for (const auto& p : exposed_polygon(f)) {
      pts.push_back({p.x(), p.y(), 0.0});  // footprint
      // Where the sun ray through p meets the ground.
      const Eigen::Vector3d s = p - sun * (p.z() / sun.z());
      pts.push_back({s.x(), s.y(), 0.0});
    }
  return convex_hull_xy(std::move(pts));
}

}  // namespace petra::sim

#include "sim/eval/proposals_picture.hpp"

#include <cmath>
#include <string>

#include "algo/chain/palette.hpp"
#include "sim/eval/tiny_font.hpp"

namespace petra::eval {

namespace {

Colour colour(palette::Rgb8 c) {
  return {c.r, c.g, c.b};
}

void draw_box(io::RgbImage& img, const Rect& r, Colour c) {
  const int x1 = r.x + r.w - 1, y1 = r.y + r.h - 1;
  draw_line(img, r.x, r.y, x1, r.y, c, 2);
  draw_line(img, x1, r.y, x1, y1, c, 2);
  draw_line(img, x1, y1, r.x, y1, c, 2);
  draw_line(img, r.x, y1, r.x, r.y, c, 2);
}

// The best plane: the first offered, else the first.
int best_plane(const RockProposal& p) {
  for (int k = 0; k < p.plane_count; ++k)
    if (p.planes[k].verdict == PlaneVerdict::accepted && p.reach[k] == arm::ArmReason::ok) return k;
  return p.plane_count > 0 ? 0 : -1;
}

void draw_plane(io::RgbImage& img, const TsaiCamera& camera, const GrindPlane& g, Colour c) {
  auto a = project(camera, g.face_centroid_mm);
  auto b = project(camera, g.face_centroid_mm + 30.0 * g.normal);
  if (!a) return;
  const int ax = static_cast<int>(std::lround(a->x())), ay = static_cast<int>(std::lround(a->y()));
  draw_disc(img, ax, ay, 5, c);
  if (b)
    draw_line(img, ax, ay, static_cast<int>(std::lround(b->x())),
              static_cast<int>(std::lround(b->y())), c, 2);
}

}  // namespace

io::RgbImage proposals_picture(ConstGray8View left, const TsaiCamera& camera,
                               const ProposalList& list) {
  io::RgbImage img(left.width(), left.height());
  for (int y = 0; y < left.height(); ++y)
    for (int x = 0; x < left.width(); ++x)
      for (int k = 0; k < 3; ++k)
        img.rgb[(static_cast<std::size_t>(y) * left.width() + x) * 3 + k] = left(x, y);
  const Colour white{255, 255, 255};
  for (int i = list.count - 1; i >= 0; --i) {  // rank 1 drawn last, on top
    const RockProposal& p = list.items[i];
    const int best = best_plane(p);
    const bool offered = p.note == ProposalNote::ok;
    const Colour c = colour(offered ? palette::plane_colour(i) : palette::kRejected);
    draw_box(img, p.rock.roi, c);
    draw_text(img, p.rock.roi.x + 4, p.rock.roi.y + 4, std::to_string(i + 1), c, 3);
    draw_line(img, p.rock.click_u - 6, p.rock.click_v, p.rock.click_u + 6, p.rock.click_v, white);
    draw_line(img, p.rock.click_u, p.rock.click_v - 6, p.rock.click_u, p.rock.click_v + 6, white);
    if (best >= 0) draw_plane(img, camera, p.planes[best], c);
  }
  if (list.count == 0 || list.items[0].note != ProposalNote::ok)
    draw_text(img, 8, 8, "NO PROPOSAL", white, 2);
  return img;
}

}  // namespace petra::eval

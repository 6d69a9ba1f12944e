#include "fsw/proposal_picture.hpp"

#include <algorithm>

#include "algo/chain/palette.hpp"
#include "fsw/proposal_packet.hpp"

namespace petra::fsw {

namespace {

constexpr int kCrossArm = 4;  // px of the picture
constexpr int kDash = 4;      // dashed frame: 4 px on, 4 off

struct Canvas {
  ImageView<std::uint8_t> rgb;
  int w = 0;  // pixels
  int h = 0;
  void put(int x, int y, palette::Rgb8 c) const {
    if (x < 0 || y < 0 || x >= w || y >= h) return;
    std::uint8_t* p = rgb.row(y) + 3 * x;
    p[0] = c.r;
    p[1] = c.g;
    p[2] = c.b;
  }
};

void frame(const Canvas& cv, Rect r, palette::Rgb8 c, bool dashed) {
  for (int t = 0; t < 2; ++t) {  // 2 px wide, inside the ROI
    const int x0 = r.x + t, y0 = r.y + t, x1 = r.x + r.w - 1 - t, y1 = r.y + r.h - 1 - t;
    for (int x = x0; x <= x1; ++x)
      if (!dashed || (x / kDash) % 2 == 0) {
        cv.put(x, y0, c);
        cv.put(x, y1, c);
      }
    for (int y = y0; y <= y1; ++y)
      if (!dashed || (y / kDash) % 2 == 0) {
        cv.put(x0, y, c);
        cv.put(x1, y, c);
      }
  }
}

void cross(const Canvas& cv, int u, int v, palette::Rgb8 c) {
  for (int d = -kCrossArm; d <= kCrossArm; ++d) {
    cv.put(u + d, v, c);
    cv.put(u, v + d, c);
  }
}

}  // namespace

void draw_proposals(ImageView<std::uint8_t> rgb, int step, const ProposalList& list) {
  if (step < 1) return;
  const Canvas cv{rgb, rgb.width() / 3, rgb.height()};
  // Worst rank first, so the best proposal's frame is on top where they overlap.
  for (int i = std::min(list.count, kMaxProposals) - 1; i >= 0; --i) {
    const RockProposal& p = list.items[i];
    const bool offered = offered_plane(p) >= 0;
    const palette::Rgb8 c = offered ? palette::plane_colour(i) : palette::kRejected;
    const Rect r = p.rock.roi;
    frame(cv, Rect{r.x / step, r.y / step, std::max(r.w / step, 1), std::max(r.h / step, 1)}, c,
          !offered);
    cross(cv, p.rock.click_u / step, p.rock.click_v / step, c);
  }
}

}  // namespace petra::fsw

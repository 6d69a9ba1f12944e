// A gray image that owns its pixels, for tests that build inputs by hand
// (tests may allocate; the code under test gets a view).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "algo/core/image_view.hpp"

namespace petra::test {

struct OwnedGray8 {
  int w, h;
  std::vector<std::uint8_t> px;
  OwnedGray8(int w_, int h_, std::uint8_t v = 0)
      : w(w_), h(h_), px(static_cast<std::size_t>(w_) * static_cast<std::size_t>(h_), v) {}
  Gray8View view() { return {px.data(), w, h}; }
  std::uint8_t& at(int x, int y) {
    return px[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) +
              static_cast<std::size_t>(x)];
  }
};

}  // namespace petra::test

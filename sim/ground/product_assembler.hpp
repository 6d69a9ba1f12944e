// Reassembles PRODUCT chunks into whole products on the ground and writes
// them: images as PGM/PPM, point clouds as ASCII "x y z" lines (mm).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tlm/telemetry.hpp"

namespace petra::ground {

struct Product {
  std::uint8_t kind = 0;  // 1 LEFT_IMAGE, 2 DISPARITY, 3 OVERLAY, 4 POINT_CLOUD, 5 PROPOSALS
  std::uint8_t format = 0;
  std::uint32_t id = 0;
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> bytes;
};

const char* product_name(std::uint8_t kind);

class ProductAssembler {
 public:
  // Adds a chunk; returns the product when this chunk completes it.
  std::optional<Product> add(const tlm::Product& chunk);
  // Chunks of products never completed (lost packets).
  std::size_t incomplete() const { return partial_.size(); }
  // Those products, "<name> <id> (<got> of <total> chunks)", comma-separated.
  std::string incomplete_text() const;

 private:
  struct Partial {
    Product product;
    std::vector<bool> have;
    std::size_t count = 0;
  };
  std::map<std::pair<int, std::uint32_t>, Partial> partial_;
};

// Writes DIR/<name>_<id>.pgm|.ppm|.xyz; returns the path.
std::string write_product(const Product& p, const std::string& dir);

}  // namespace petra::ground

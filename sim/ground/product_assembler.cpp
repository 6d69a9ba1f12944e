#include "sim/ground/product_assembler.hpp"

#include <bit>
#include <cstring>
#include <fstream>

namespace petra::ground {

const char* product_name(std::uint8_t kind) {
  switch (kind) {
    case 1:
      return "left_image";
    case 2:
      return "disparity";
    case 3:
      return "overlay";
    case 4:
      return "point_cloud";
    case 5:
      return "proposals";
  }
  return "product";
}

std::string ProductAssembler::incomplete_text() const {
  std::string text;
  for (const auto& [key, p] : partial_) {
    if (!text.empty()) text += ", ";
    text += std::string(product_name(p.product.kind)) + " " + std::to_string(p.product.id) + " (" +
            std::to_string(p.count) + " of " + std::to_string(p.have.size()) + " chunks)";
  }
  return text;
}

std::optional<Product> ProductAssembler::add(const tlm::Product& c) {
  if (c.chunks == 0 || c.chunk >= c.chunks || c.total_bytes > 64u << 20) return std::nullopt;
  const auto key = std::make_pair(int{c.product}, c.id);
  auto& p = partial_[key];
  if (p.have.size() != c.chunks || p.product.bytes.size() != c.total_bytes) {  // new (or restarted)
    p = Partial{};
    p.product = Product{c.product, c.format, c.id,
                        c.width,   c.height, std::vector<std::uint8_t>(c.total_bytes)};
    p.have.assign(c.chunks, false);
  }
  const std::size_t at = static_cast<std::size_t>(c.chunk) * PETRA_PRODUCT_DATA_BYTES;
  if (at + c.data_len > p.product.bytes.size()) return std::nullopt;
  std::memcpy(p.product.bytes.data() + at, c.data.data(), c.data_len);
  if (!p.have[c.chunk]) {
    p.have[c.chunk] = true;
    ++p.count;
  }
  if (p.count < c.chunks) return std::nullopt;
  Product done = std::move(p.product);
  partial_.erase(key);
  return done;
}

std::string write_product(const Product& p, const std::string& dir) {
  std::string path = dir + "/" + product_name(p.kind) + "_" + std::to_string(p.id);
  if (p.format == 1 || p.format == 2) {
    path += p.format == 1 ? ".pgm" : ".ppm";
    std::ofstream f(path, std::ios::binary);
    f << (p.format == 1 ? "P5" : "P6") << "\n" << p.width << " " << p.height << "\n255\n";
    f.write(reinterpret_cast<const char*>(p.bytes.data()),
            static_cast<std::streamsize>(p.bytes.size()));
  } else {
    path += ".xyz";
    std::ofstream f(path);
    for (std::size_t i = 0; i + 12 <= p.bytes.size(); i += 12) {
      float xyz[3];
      for (int k = 0; k < 3; ++k) {
        const std::uint8_t* b = p.bytes.data() + i + 4 * static_cast<std::size_t>(k);
        const std::uint32_t u = (std::uint32_t{b[0]} << 24) | (std::uint32_t{b[1]} << 16) |
                                (std::uint32_t{b[2]} << 8) | b[3];
        xyz[k] = std::bit_cast<float>(u);
      }
      f << xyz[0] << " " << xyz[1] << " " << xyz[2] << "\n";
    }
  }
  return path;
}

}  // namespace petra::ground

#include "sim/io/image_io.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

namespace petra::io {
namespace {

std::string tmp(const char* name) {
  return (std::filesystem::temp_directory_path() / (std::string("petra_io_") + name)).string();
}

GrayImage gradient(int w, int h) {
  GrayImage g(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) g.view()(x, y) = static_cast<std::uint8_t>((x * 7 + y * 13) & 255);
  return g;
}

TEST(ImageIo, PgmAndPngRoundTrip) {
  const GrayImage g = gradient(37, 23);
  ASSERT_TRUE(write_pgm(tmp("a.pgm"), g.view()).ok());
  ASSERT_TRUE(write_png(tmp("a.png"), g.view()).ok());
  for (const char* f : {"a.pgm", "a.png"}) {
    auto r = read_gray_image(tmp(f));
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_EQ(r->width, 37);
    EXPECT_EQ(r->height, 23);
    EXPECT_EQ(r->pixels, g.pixels) << f;
  }
}

TEST(ImageIo, PfmRoundTripKeepsInfAndRowOrder) {
  FloatImage d(5, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) d.view()(x, y) = static_cast<float>(10 * y + x) + 0.25f;
  d.view()(2, 1) = std::numeric_limits<float>::infinity();
  ASSERT_TRUE(write_pfm(tmp("d.pfm"), d.view()).ok());
  auto r = read_pfm(tmp("d.pfm"));
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->data[0], 0.25f);        // top-left
  EXPECT_EQ(r->view()(4, 2), 24.25f);  // bottom-right
  EXPECT_TRUE(std::isinf(r->view()(2, 1)));
}

TEST(ImageIo, ReadsMiddleburyFormats) {
  const std::string data = std::string(PETRA_SOURCE_DIR) + "/../shared/data/middlebury/";
  auto tsukuba = read_gray_image(data + "tsukuba/scene1.row3.col3.ppm");
  ASSERT_TRUE(tsukuba.ok()) << tsukuba.error().message;
  EXPECT_EQ(tsukuba->width, 384);
  EXPECT_EQ(tsukuba->height, 288);
  auto teddy = read_gray_image(data + "teddy/im2.png");
  ASSERT_TRUE(teddy.ok()) << teddy.error().message;
  EXPECT_EQ(teddy->width, 450);
  EXPECT_EQ(teddy->height, 375);
  auto rgb = read_rgb_image(data + "teddy/im2.png");
  ASSERT_TRUE(rgb.ok());
  const std::uint8_t* p = rgb->at(100, 100);
  EXPECT_EQ(teddy->view()(100, 100), rgb_to_gray(p[0], p[1], p[2]));
  auto gt = read_gray_image(data + "map/disp0.pgm");
  ASSERT_TRUE(gt.ok());
  EXPECT_EQ(gt->width, 284);
}

TEST(ImageIo, ReadsJpeg) {
  const std::string data = std::string(PETRA_SOURCE_DIR) + "/../shared/data/chessboard-opencv/";
  auto g = read_gray_image(data + "left01.jpg");
  ASSERT_TRUE(g.ok()) << g.error().message;
  EXPECT_EQ(g->width, 640);
  EXPECT_EQ(g->height, 480);
  auto rgb = read_rgb_image(data + "left01.jpg");
  ASSERT_TRUE(rgb.ok()) << rgb.error().message;
  // A gray JPEG expands to equal channels that match the gray read.
  const std::uint8_t* p = rgb->at(320, 240);
  EXPECT_EQ(p[0], p[1]);
  EXPECT_EQ(p[0], g->view()(320, 240));
}

TEST(ImageIo, DamagedJpegNamesTheProblem) {
  const std::string data = std::string(PETRA_SOURCE_DIR) + "/../shared/data/chessboard-opencv/";
  auto bytes = read_text_file(data + "left01.jpg");
  ASSERT_TRUE(bytes.ok());
  // Cut inside the header: libjpeg stops with a reason; never a crash.
  ASSERT_TRUE(write_text_file(tmp("cut.jpg"), bytes->substr(0, 100)).ok());
  auto r = read_gray_image(tmp("cut.jpg"));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.code(), Errc::parse_error);
  EXPECT_NE(std::string(r.error().message).find("cut.jpg"), std::string::npos) << r.error().message;
  // Just the start-of-image marker.
  ASSERT_TRUE(write_text_file(tmp("soi.jpg"), "\xff\xd8\xff\xe0").ok());
  EXPECT_EQ(read_gray_image(tmp("soi.jpg")).code(), Errc::parse_error);
}

TEST(ImageIo, GrayConversionMatchesOpenCvWeights) {
  EXPECT_EQ(rgb_to_gray(255, 255, 255), 255);
  EXPECT_EQ(rgb_to_gray(0, 0, 0), 0);
  EXPECT_EQ(rgb_to_gray(255, 0, 0), 76);   // 0.299 * 255
  EXPECT_EQ(rgb_to_gray(0, 255, 0), 150);  // 0.587 * 255
  EXPECT_EQ(rgb_to_gray(0, 0, 255), 29);   // 0.114 * 255
}

TEST(ImageIo, MalformedFilesNameTheProblem) {
  const std::pair<const char*, const char*> cases[] = {
      {"P5\n10 10\n255\nshort", "truncated"},
      {"P5\n-3 10\n255\n", "width"},
      {"P9\n1 1\n255\n", "magic"},
      {"\x89PNG\r\n\x1a\nbroken", ""},
      {"hello", "unknown image format"},
      {"", "unknown image format"},
      {"P2\n2 1\n255\n1 300\n", "maxval"},
  };
  for (const auto& [text, what] : cases) {
    ASSERT_TRUE(write_text_file(tmp("bad"), text).ok());
    auto r = read_gray_image(tmp("bad"));
    ASSERT_FALSE(r.ok()) << text;
    EXPECT_NE(std::string(r.error().message).find(what), std::string::npos) << r.error().message;
  }
  EXPECT_EQ(read_gray_image(tmp("does-not-exist")).code(), Errc::io_error);
  ASSERT_TRUE(write_text_file(tmp("bad.pfm"), "Pf\n4 4\n-1\n").ok());
  EXPECT_EQ(read_pfm(tmp("bad.pfm")).code(), Errc::parse_error);
}

}  // namespace
}  // namespace petra::io

#include "hal/file_stereo_camera.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <vector>

#include "tests/support/heap_counter.hpp"

namespace petra::hal {
namespace {

namespace fs = std::filesystem;

void pgm(const fs::path& p, int w, int h, int v, const char* header_extra = "") {
  std::ofstream f(p, std::ios::binary);
  f << "P5\n" << header_extra << w << " " << h << "\n255\n";
  for (int i = 0; i < w * h; ++i) f.put(static_cast<char>((v + i) & 0xFF));
}

struct TempDir {
  TempDir()
      : path(fs::temp_directory_path() /
             ("petra_cam_" + std::to_string(::getpid()) + "_" + std::to_string(n++))) {
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
  fs::path path;
  static inline int n = 0;
};

TEST(FileStereoCamera, PlaysPairsInNameOrderAndCycles) {
  TempDir d;
  pgm(d.path / "left_002.pgm", 8, 4, 20);
  pgm(d.path / "right_002.pgm", 8, 4, 21);
  pgm(d.path / "left_001.pgm", 8, 4, 10, "# a comment\n");
  pgm(d.path / "right_001.pgm", 8, 4, 11);
  pgm(d.path / "left_003.pgm", 8, 4, 30);  // no right: not a pair
  FileStereoCamera cam;
  ASSERT_TRUE(cam.open(d.path.c_str()).ok());
  EXPECT_EQ(cam.pairs(), 2u);
  EXPECT_EQ(cam.width(), 8);
  std::vector<std::uint8_t> l(32), r(32);
  const std::uint8_t firsts[] = {10, 20, 10};
  for (int i = 0; i < 3; ++i) {
    petra::test::HeapScope scope;
    auto meta = cam.acquire(Gray8View(l.data(), 8, 4), Gray8View(r.data(), 8, 4));
    ASSERT_TRUE(meta.ok()) << meta.error().message;
    EXPECT_EQ(scope.allocations(), 0u);
    EXPECT_EQ(meta->sequence, static_cast<std::uint32_t>(i + 1));
    EXPECT_EQ(l[0], firsts[i]);
    EXPECT_EQ(r[0], firsts[i] + 1);
    EXPECT_EQ(l[31], firsts[i] + 31);
  }
}

TEST(FileStereoCamera, RefusesBadFoldersAndFilesNamingThem) {
  TempDir d;
  FileStereoCamera cam;
  auto s = cam.open(d.path.c_str());
  ASSERT_FALSE(s.ok());
  EXPECT_NE(std::string(s.error().message).find("no left"), std::string::npos);
  pgm(d.path / "left.pgm", 8, 4, 0);
  pgm(d.path / "right.pgm", 9, 4, 0);
  s = cam.open(d.path.c_str());
  ASSERT_FALSE(s.ok());
  EXPECT_NE(std::string(s.error().message).find("right.pgm"), std::string::npos);
  std::ofstream(d.path / "right.pgm", std::ios::binary) << "P2\n8 4\n255\n";
  s = cam.open(d.path.c_str());
  ASSERT_FALSE(s.ok());
  EXPECT_NE(std::string(s.error().message).find("P5"), std::string::npos);
}

TEST(FileStereoCamera, MovesPastACorruptPairInsteadOfStickingOnIt) {
  TempDir d;
  pgm(d.path / "left_001.pgm", 8, 4, 10);
  pgm(d.path / "right_001.pgm", 8, 4, 11);
  pgm(d.path / "left_002.pgm", 8, 4, 20);
  // A valid header (open() accepts it) over too few pixels: corrupt.
  std::ofstream(d.path / "right_002.pgm", std::ios::binary) << "P5\n8 4\n255\nabc";
  pgm(d.path / "left_003.pgm", 8, 4, 30);
  pgm(d.path / "right_003.pgm", 8, 4, 31);
  FileStereoCamera cam;
  ASSERT_TRUE(cam.open(d.path.c_str()).ok());
  std::vector<std::uint8_t> l(32), r(32);
  const auto acquire = [&] {
    return cam.acquire(Gray8View(l.data(), 8, 4), Gray8View(r.data(), 8, 4));
  };
  // Two passes over the folder: pair 2 fails each time, pairs 3 and 1 follow it.
  for (int pass = 0; pass < 2; ++pass) {
    auto m = acquire();
    ASSERT_TRUE(m.ok()) << m.error().message;
    EXPECT_EQ(l[0], 10);
    {
      petra::test::HeapScope scope;
      m = acquire();
      EXPECT_EQ(scope.allocations(), 0u);
    }
    ASSERT_FALSE(m.ok());
    EXPECT_EQ(m.code(), Errc::parse_error);
    EXPECT_NE(std::string(m.error().message).find("pair 2 of 3 skipped"), std::string::npos)
        << m.error().message;
    EXPECT_NE(std::string(m.error().message).find("right_002.pgm"), std::string::npos);
    m = acquire();
    ASSERT_TRUE(m.ok()) << m.error().message;
    EXPECT_EQ(m->source_index, 2u);
    EXPECT_EQ(l[0], 30);
    EXPECT_EQ(r[0], 31);
  }
  EXPECT_EQ(cam.skipped(), 2u);
}

TEST(PgmReader, TruncatedFileIsAnErrorNotACrash) {
  TempDir d;
  std::ofstream(d.path / "t.pgm", std::ios::binary) << "P5\n8 4\n255\nabc";
  PgmReader r;
  std::vector<std::uint8_t> px(32);
  auto s = r.read((d.path / "t.pgm").c_str(), Gray8View(px.data(), 8, 4));
  ASSERT_FALSE(s.ok());
  EXPECT_NE(std::string(s.error().message).find("truncated"), std::string::npos);
  std::ofstream(d.path / "w.pgm", std::ios::binary) << "P5\n8 4\n65535\n";
  EXPECT_FALSE(r.read_size((d.path / "w.pgm").c_str()).ok());
}

}  // namespace
}  // namespace petra::hal

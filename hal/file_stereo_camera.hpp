// A stereo camera backed by a folder of PGM pairs, so the service runs
// anywhere: every file named left<suffix>.pgm with a right<suffix>.pgm beside
// it is one pair (left.pgm/right.pgm, left_001.pgm/right_001.pgm, ...), taken
// in name order and cycled. open() scans the folder (init); acquire() reads
// with a fixed buffer and allocates nothing. A pair that fails to read (a
// corrupt or vanished file) is an error for that call and is skipped: the
// next call reads the next pair (the executive raises CAMERA_FAULT and retries).
#pragma once

#include <array>

#include "algo/core/fixed_vector.hpp"
#include "hal/pgm_reader.hpp"
#include "hal/stereo_camera.hpp"

namespace petra::hal {

class FileStereoCamera final : public StereoCamera {
 public:
  static constexpr std::size_t kMaxPairs = 64;
  static constexpr std::size_t kMaxPath = 256;

  // Scans dir; every pair must have the same size (that of the first pair).
  Status open(const char* dir);

  const char* name() const override { return "file"; }
  int width() const override { return size_.width; }
  int height() const override { return size_.height; }
  std::size_t pairs() const { return pairs_.size(); }
  // Pairs that failed to read and were skipped since open().
  std::uint32_t skipped() const { return skipped_; }
  Result<FrameMeta> acquire(Gray8View left, Gray8View right) override;

 private:
  struct Pair {
    std::array<char, kMaxPath> left{};
    std::array<char, kMaxPath> right{};
  };
  FixedVector<Pair, kMaxPairs> pairs_;
  PgmReader reader_;
  PgmSize size_;
  std::uint32_t sequence_ = 0;
  std::uint32_t skipped_ = 0;
  std::size_t next_ = 0;
};

}  // namespace petra::hal

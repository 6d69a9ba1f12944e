// Stereo image pairs from two file patterns (ground tool), e.g.
// 'DIR/left*.jpg' and 'DIR/right*.jpg'. Files pair up by the part the
// wildcards matched ("01" in left01.jpg and right01.jpg); files without a
// partner are listed so the operator sees them.
#pragma once

#include <string>
#include <vector>

#include "algo/core/result.hpp"

namespace petra::calib {

struct ImagePair {
  std::string key;  // what the wildcards matched
  std::string left, right;
};

struct ImagePairing {
  std::vector<ImagePair> pairs;       // sorted by key
  std::vector<std::string> unpaired;  // files with no partner
};

// Expands a shell pattern (glob(3)); sorted paths, or an error naming the pattern.
Result<std::vector<std::string>> expand_pattern(const std::string& pattern);

// The part of a path the wildcards of the pattern's file name matched.
std::string wildcard_key(const std::string& pattern, const std::string& path);

Result<ImagePairing> pair_images(const std::string& left_pattern, const std::string& right_pattern);

}  // namespace petra::calib

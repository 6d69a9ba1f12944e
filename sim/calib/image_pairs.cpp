#include "sim/calib/image_pairs.hpp"

#include <glob.h>

#include <algorithm>
#include <map>

namespace petra::calib {

namespace {

std::string basename_of(const std::string& p) {
  const std::size_t s = p.find_last_of('/');
  return s == std::string::npos ? p : p.substr(s + 1);
}

}  // namespace

Result<std::vector<std::string>> expand_pattern(const std::string& pattern) {
  glob_t g{};
  const int rc = glob(pattern.c_str(), 0, nullptr, &g);
  std::vector<std::string> out;
  if (rc == 0)
    for (std::size_t k = 0; k < g.gl_pathc; ++k) out.emplace_back(g.gl_pathv[k]);
  globfree(&g);
  if (rc == GLOB_NOMATCH || (rc == 0 && out.empty()))
    return Error::make(Errc::io_error, "no files match '%s'", pattern.c_str());
  if (rc != 0) return Error::make(Errc::io_error, "cannot expand '%s'", pattern.c_str());
  std::sort(out.begin(), out.end());
  return out;
}

std::string wildcard_key(const std::string& pattern, const std::string& path) {
  const std::string pat = basename_of(pattern), name = basename_of(path);
  const std::size_t first = pat.find_first_of("*?[");
  if (first == std::string::npos) return "";
  // Literal suffix after the last wildcard (a bracket expression ends at ']').
  std::size_t last = pat.find_last_of("*?]");
  const std::string prefix = pat.substr(0, first), suffix = pat.substr(last + 1);
  if (name.size() < prefix.size() + suffix.size()) return name;
  return name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
}

Result<ImagePairing> pair_images(const std::string& left_pattern,
                                 const std::string& right_pattern) {
  auto left = expand_pattern(left_pattern);
  if (!left) return left.error();
  auto right = expand_pattern(right_pattern);
  if (!right) return right.error();
  std::map<std::string, std::string> l, r;
  ImagePairing out;
  for (const std::string& p : *left)
    if (!l.emplace(wildcard_key(left_pattern, p), p).second) out.unpaired.push_back(p);
  for (const std::string& p : *right)
    if (!r.emplace(wildcard_key(right_pattern, p), p).second) out.unpaired.push_back(p);
  for (const auto& [key, path] : l) {
    const auto it = r.find(key);
    if (it == r.end()) {
      out.unpaired.push_back(path);
      continue;
    }
    out.pairs.push_back({key, path, it->second});
  }
  for (const auto& [key, path] : r)
    if (l.find(key) == l.end()) out.unpaired.push_back(path);
  return out;
}

}  // namespace petra::calib

// Typed field access on a parsed JSON document for the ground tools, with
// errors that name the file and the field path ("truth.json: facets[2].normal:
// expected an array of 3 numbers").
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "algo/core/json_reader.hpp"
#include "algo/core/result.hpp"

namespace petra::sim {

// A text and its tokens, parsed once; holds the memory the document refers to.
class JsonFile {
 public:
  // `name` prefixes every error message (usually the file name).
  static Result<JsonFile> parse(std::string text, std::string name);

  JsonFile(const JsonFile&) = delete;
  JsonFile& operator=(const JsonFile&) = delete;
  JsonFile(JsonFile&& other) noexcept;

  const json::Document& doc() const { return doc_; }
  const std::string& name() const { return name_; }

  // Members of object `obj`: required ones fail when absent.
  Result<std::uint32_t> member(std::uint32_t obj, std::string_view key,
                               const std::string& path) const;
  std::uint32_t optional_member(std::uint32_t obj, std::string_view key) const;

  Result<std::uint32_t> object(std::uint32_t i, const std::string& path) const;
  Result<std::uint32_t> array(std::uint32_t i, const std::string& path) const;
  Result<double> number(std::uint32_t i, const std::string& path) const;
  Result<long long> integer(std::uint32_t i, const std::string& path) const;
  Result<bool> boolean(std::uint32_t i, const std::string& path) const;
  // A string's raw text (escapes left as written).
  Result<std::string> string(std::uint32_t i, const std::string& path) const;
  Result<Eigen::Vector3d> vec3(std::uint32_t i, const std::string& path) const;
  // A unit vector: length within 1e-3 of 1 (then normalised exactly).
  Result<Eigen::Vector3d> unit_vec3(std::uint32_t i, const std::string& path) const;

  // Indices of the elements of array `arr`, in order.
  std::vector<std::uint32_t> elements(std::uint32_t arr) const;

  Error error(const std::string& path, const char* what) const;

 private:
  JsonFile() = default;
  std::string text_;
  std::string name_;
  std::vector<json::Token> tokens_;
  json::Document doc_;
};

}  // namespace petra::sim

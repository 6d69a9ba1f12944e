// A heap-free JSON reader: tokenises a text into a caller-provided token array
// (one token per value, object key or container) and answers lookups on it.
// Used at init for calib.json and parameter files; never on the hot path.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "algo/core/result.hpp"

namespace petra::json {

enum class Type : std::uint8_t { null, boolean, number, string, array, object };

const char* type_name(Type t);

struct Token {
  Type type = Type::null;
  std::uint32_t begin = 0;  // offset of the first character (strings: after the quote)
  std::uint32_t end = 0;    // one past the last character (strings: before the quote)
  std::uint32_t next = 0;   // index of the token after this one's subtree
  std::uint32_t count = 0;  // containers: number of elements (objects: number of members)
  double number = 0.0;      // numbers: parsed value; booleans: 0 or 1
};

// A parsed document. Object members are stored key token then value token.
class Document {
 public:
  // Parses `text` into `tokens`. Errors name the byte offset.
  static Result<Document> parse(std::string_view text, std::span<Token> tokens);

  // Root token index is 0.
  const Token& token(std::uint32_t i) const { return tokens_[i]; }
  std::string_view text_of(std::uint32_t i) const {
    return text_.substr(tokens_[i].begin, tokens_[i].end - tokens_[i].begin);
  }
  std::uint32_t size() const { return size_; }

  // Index of the value of `key` in object `obj`, or 0 when absent (0 is the root,
  // never a member value).
  std::uint32_t find(std::uint32_t obj, std::string_view key) const;
  // Index of element `n` of array `arr`, or 0 when out of range.
  std::uint32_t element(std::uint32_t arr, std::uint32_t n) const;

 private:
  std::string_view text_;
  std::span<Token> tokens_;
  std::uint32_t size_ = 0;
};

}  // namespace petra::json

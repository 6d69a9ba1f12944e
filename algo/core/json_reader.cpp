#include "algo/core/json_reader.hpp"

#include <charconv>
#include <cmath>

namespace petra::json {

const char* type_name(Type t) {
  switch (t) {
    case Type::null:
      return "null";
    case Type::boolean:
      return "boolean";
    case Type::number:
      return "number";
    case Type::string:
      return "string";
    case Type::array:
      return "array";
    case Type::object:
      return "object";
  }
  return "?";
}

namespace {

constexpr int kMaxDepth = 32;  // bounded nesting: no unbounded recursion

class Parser {
 public:
  Parser(std::string_view text, std::span<Token> tokens) : text_(text), tokens_(tokens) {}

  Status run(std::uint32_t& count) {
    skip_ws();
    PETRA_TRY(value(0));
    skip_ws();
    if (pos_ != text_.size()) return fail("trailing characters");
    count = used_;
    return {};
  }

 private:
  Error fail(const char* what) const {
    return Error::make(Errc::parse_error, "json: %s at byte %zu", what, pos_);
  }

  void skip_ws() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t' ||
                                   text_[pos_] == '\n' || text_[pos_] == '\r'))
      ++pos_;
  }

  Result<std::uint32_t> new_token(Type t) {
    if (used_ >= tokens_.size())
      return Error::make(Errc::capacity_exceeded, "json: more than %zu tokens", tokens_.size());
    tokens_[used_] = Token{};
    tokens_[used_].type = t;
    tokens_[used_].begin = static_cast<std::uint32_t>(pos_);
    return used_++;
  }

  Status value(int depth) {
    if (depth > kMaxDepth) return fail("nesting too deep");
    if (pos_ >= text_.size()) return fail("unexpected end");
    const char c = text_[pos_];
    if (c == '{') return container(depth, Type::object);
    if (c == '[') return container(depth, Type::array);
    if (c == '"') return string();
    if (c == 't') return literal("true", Type::boolean, 1.0);
    if (c == 'f') return literal("false", Type::boolean, 0.0);
    if (c == 'n') return literal("null", Type::null, 0.0);
    return number();
  }

  Status literal(std::string_view word, Type t, double v) {
    if (text_.substr(pos_, word.size()) != word) return fail("invalid literal");
    auto idx = new_token(t);
    if (!idx) return idx.error();
    pos_ += word.size();
    Token& tok = tokens_[*idx];
    tok.end = static_cast<std::uint32_t>(pos_);
    tok.number = v;
    tok.next = used_;
    return {};
  }

  Status number() {
    auto idx = new_token(Type::number);
    if (!idx) return idx.error();
    std::size_t p = pos_;
    // JSON grammar check (std::from_chars alone would accept e.g. "inf").
    if (p < text_.size() && text_[p] == '-') ++p;
    if (p >= text_.size() || text_[p] < '0' || text_[p] > '9') return fail("invalid number");
    while (p < text_.size() &&
           ((text_[p] >= '0' && text_[p] <= '9') || text_[p] == '.' || text_[p] == 'e' ||
            text_[p] == 'E' || text_[p] == '+' || text_[p] == '-'))
      ++p;
    double v = 0.0;
    const char* first = text_.data() + pos_;
    const char* last = text_.data() + p;
    auto [ptr, ec] = std::from_chars(first, last, v);
    if (ec != std::errc{} || ptr != last || !std::isfinite(v)) return fail("invalid number");
    pos_ = p;
    Token& tok = tokens_[*idx];
    tok.end = static_cast<std::uint32_t>(pos_);
    tok.number = v;
    tok.next = used_;
    return {};
  }

  Status string() {
    ++pos_;  // opening quote
    auto idx = new_token(Type::string);
    if (!idx) return idx.error();
    while (pos_ < text_.size() && text_[pos_] != '"') {
      const auto ch = static_cast<unsigned char>(text_[pos_]);
      if (ch < 0x20) return fail("control character in string");
      if (ch == '\\') {
        ++pos_;
        if (pos_ >= text_.size()) return fail("unterminated escape");
      }
      ++pos_;
    }
    if (pos_ >= text_.size()) return fail("unterminated string");
    Token& tok = tokens_[*idx];
    tok.end = static_cast<std::uint32_t>(pos_);
    ++pos_;  // closing quote
    tok.next = used_;
    return {};
  }

  Status container(int depth, Type t) {
    auto idx = new_token(t);
    if (!idx) return idx.error();
    const char close = t == Type::object ? '}' : ']';
    ++pos_;
    skip_ws();
    std::uint32_t n = 0;
    if (pos_ < text_.size() && text_[pos_] == close) {
      ++pos_;
    } else {
      for (;;) {
        if (t == Type::object) {
          skip_ws();
          if (pos_ >= text_.size() || text_[pos_] != '"') return fail("expected a key");
          PETRA_TRY(string());
          skip_ws();
          if (pos_ >= text_.size() || text_[pos_] != ':') return fail("expected ':'");
          ++pos_;
        }
        skip_ws();
        PETRA_TRY(value(depth + 1));
        ++n;
        skip_ws();
        if (pos_ < text_.size() && text_[pos_] == ',') {
          ++pos_;
          continue;
        }
        if (pos_ < text_.size() && text_[pos_] == close) {
          ++pos_;
          break;
        }
        return fail(t == Type::object ? "expected ',' or '}'" : "expected ',' or ']'");
      }
    }
    Token& tok = tokens_[*idx];
    tok.end = static_cast<std::uint32_t>(pos_);
    tok.count = n;
    tok.next = used_;
    return {};
  }

  std::string_view text_;
  std::span<Token> tokens_;
  std::size_t pos_ = 0;
  std::uint32_t used_ = 0;
};

}  // namespace

Result<Document> Document::parse(std::string_view text, std::span<Token> tokens) {
  if (text.size() >= UINT32_MAX)
    return Error::make(Errc::capacity_exceeded, "json: text too large");
  Parser p(text, tokens);
  std::uint32_t count = 0;
  PETRA_TRY(p.run(count));
  Document d;
  d.text_ = text;
  d.tokens_ = tokens;
  d.size_ = count;
  return d;
}

std::uint32_t Document::find(std::uint32_t obj, std::string_view key) const {
  if (obj >= size_ || tokens_[obj].type != Type::object) return 0;
  std::uint32_t i = obj + 1;
  for (std::uint32_t m = 0; m < tokens_[obj].count; ++m) {
    const std::uint32_t value = i + 1;
    if (text_of(i) == key) return value;
    i = tokens_[value].next;
  }
  return 0;
}

std::uint32_t Document::element(std::uint32_t arr, std::uint32_t n) const {
  if (arr >= size_ || tokens_[arr].type != Type::array || n >= tokens_[arr].count) return 0;
  std::uint32_t i = arr + 1;
  for (std::uint32_t k = 0; k < n; ++k) i = tokens_[i].next;
  return i;
}

}  // namespace petra::json

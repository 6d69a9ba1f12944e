// libFuzzer target over the JSON reader and the two documents it reads from
// outside the flight code's control: the service configuration
// (fsw/config: parse_config) and the calibration (algo/camera/calib_json).
// Properties: no crash or sanitizer report; a parsed document's tokens lie
// inside the text and each token's subtree ends after it.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "algo/camera/calib_json.hpp"
#include "algo/core/json_reader.hpp"
#include "fsw/config.hpp"

namespace {

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "fuzz property violated: %s\n", what);
    std::abort();
  }
}

void check_document(std::string_view text) {
  using namespace petra::json;
  static Token tokens[256];
  auto doc = Document::parse(text, tokens);
  if (!doc) return;
  check(doc->size() >= 1 && doc->size() <= 256, "token count out of range");
  for (std::uint32_t i = 0; i < doc->size(); ++i) {
    const Token& t = doc->token(i);
    check(t.begin <= t.end && t.end <= text.size(), "token outside the text");
    check(t.next > i && t.next <= doc->size(), "subtree does not end after its token");
    if (t.type == Type::array)
      for (std::uint32_t k = 0; k <= t.count; ++k) (void)doc->element(i, k);
    if (t.type == Type::object) (void)doc->find(i, "camera");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  check_document(text);
  (void)petra::parse_calib_json(text);
  (void)petra::fsw::parse_config(text.data(), text.size(), "/nonexistent");
  return 0;
}

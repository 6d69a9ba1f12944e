#include <gtest/gtest.h>

#include <array>
#include <cstring>

#include "algo/core/json_reader.hpp"
#include "algo/core/json_writer.hpp"
#include "tests/support/heap_counter.hpp"

namespace petra::json {
namespace {

TEST(JsonReader, FindsNestedValues) {
  std::array<Token, 64> tokens;
  const char* text = R"({"a": 1.5, "b": {"c": [1, 2, 3], "d": "hi"}, "e": true, "f": null})";
  auto doc = Document::parse(text, tokens);
  ASSERT_TRUE(doc.ok()) << doc.error().message;
  EXPECT_DOUBLE_EQ(doc->token(doc->find(0, "a")).number, 1.5);
  const auto b = doc->find(0, "b");
  const auto c = doc->find(b, "c");
  EXPECT_EQ(doc->token(c).count, 3u);
  EXPECT_DOUBLE_EQ(doc->token(doc->element(c, 2)).number, 3.0);
  EXPECT_EQ(doc->text_of(doc->find(b, "d")), "hi");
  EXPECT_EQ(doc->token(doc->find(0, "e")).type, Type::boolean);
  EXPECT_EQ(doc->token(doc->find(0, "f")).type, Type::null);
  EXPECT_EQ(doc->find(0, "zz"), 0u);
  EXPECT_EQ(doc->element(c, 3), 0u);
}

TEST(JsonReader, RejectsMalformedTextWithOffset) {
  std::array<Token, 16> tokens;
  const char* bad[] = {"{",           "{\"a\" 1}", "[1,]",  "{\"a\":01x}", "nul",
                       "{\"a\":1} x", "\"abc",     "[inf]", "[1e999]",     "{\"a\":-}"};
  for (const char* t : bad) {
    auto doc = Document::parse(t, tokens);
    EXPECT_FALSE(doc.ok()) << t;
    if (!doc.ok()) {
      EXPECT_EQ(doc.code(), Errc::parse_error) << t;
      EXPECT_NE(std::strstr(doc.error().message, "byte"), nullptr);
    }
  }
}

TEST(JsonReader, TokenCapacityAndDepthAreBounded) {
  std::array<Token, 3> few;
  EXPECT_EQ(Document::parse("[1,2,3,4]", few).code(), Errc::capacity_exceeded);
  std::array<Token, 200> many;
  std::string deep(100, '[');
  deep += std::string(100, ']');
  EXPECT_EQ(Document::parse(deep, many).code(), Errc::parse_error);
}

TEST(JsonWriter, RoundTripsDoublesExactly) {
  std::array<char, 256> buf;
  Writer w(buf);
  const double v = 0.1 + 0.2;
  w.begin_object().key("v").number(v).key("s").string("a\"b").key("a").begin_array();
  w.integer(-3).boolean(false).end_array().end_object();
  auto n = w.finish();
  ASSERT_TRUE(n.ok());
  std::array<Token, 16> tokens;
  auto doc = Document::parse(w.view(), tokens);
  ASSERT_TRUE(doc.ok()) << w.view();
  EXPECT_EQ(doc->token(doc->find(0, "v")).number, v);
  EXPECT_EQ(doc->token(doc->element(doc->find(0, "a"), 0)).number, -3.0);
}

TEST(JsonWriter, OverflowIsReported) {
  std::array<char, 8> buf;
  Writer w(buf);
  w.begin_object().key("long key").number(1.0).end_object();
  EXPECT_EQ(w.finish().code(), Errc::capacity_exceeded);
}

TEST(Json, NoHeap) {
  std::array<Token, 64> tokens;
  std::array<char, 256> buf;
  test::HeapScope scope;
  for (int i = 0; i < 100; ++i) {
    auto doc = Document::parse(R"({"x":[1,2,{"y":"z"}]})", tokens);
    ASSERT_TRUE(doc.ok());
    Writer w(buf);
    w.begin_object().key("k").number(3.25).end_object();
    ASSERT_TRUE(w.finish().ok());
  }
  EXPECT_EQ(scope.allocations(), 0u);
}

}  // namespace
}  // namespace petra::json

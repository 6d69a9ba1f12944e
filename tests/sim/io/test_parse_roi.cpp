#include "sim/io/parse_roi.hpp"

#include <gtest/gtest.h>

namespace petra::io {
namespace {

TEST(ParseRoi, FourIntegersMakeARect) {
  auto r = parse_roi("10,20,30,40");
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(*r, (Rect{10, 20, 30, 40}));
  EXPECT_EQ(*parse_roi("-5,0,1,1"), (Rect{-5, 0, 1, 1}));  // outside: for the caller to reject
}

TEST(ParseRoi, AnythingElseIsAnError) {
  for (const char* bad : {"", "1,2,3", "1,2,3,4,5", "1;2;3;4", "a,b,c,d", "1,2,3,4x", "1,2,0,4",
                          "1,2,3,-4", "99999999999,1,1,1"})
    EXPECT_FALSE(parse_roi(bad).ok()) << bad;
}

}  // namespace
}  // namespace petra::io

#include "sim/io/parse_point.hpp"

#include <gtest/gtest.h>

#include <string>

namespace petra::io {
namespace {

TEST(ParsePoint, TwoIntegersAndNothingElse) {
  auto p = parse_point("512,-3");
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p->u, 512);
  EXPECT_EQ(p->v, -3);
  for (const char* bad :
       {"", "12", "12,", ",4", "1,2,3", "1.5,2", "a,b", "3,4 ", "99999999999,1"}) {
    auto r = parse_point(bad);
    EXPECT_EQ(r.code(), Errc::parse_error) << bad;
  }
}

}  // namespace
}  // namespace petra::io

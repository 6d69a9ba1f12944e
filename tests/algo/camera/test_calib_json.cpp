#include "algo/camera/calib_json.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cstring>
#include <string>

#include "tests/support/heap_counter.hpp"

namespace petra {
namespace {

const char* kGood = R"({"model":"tsai-rac","units":"mm",
 "left":{"width":1024,"height":768,"f":3.8,"kappa1":-0.004,"sx":1.0,"cx":512.5,"cy":383.0,
         "dx":0.00465,"dy":0.00465,"R":[1,0,0,0,1,0,0,0,1],"T":[0,0,0]},
 "right":{"width":1024,"height":768,"f":3.81,"kappa1":-0.0041,"sx":1.001,"cx":510.0,"cy":385.0,
         "dx":0.00465,"dy":0.00465,"R":[1,0,0,0,1,0,0,0,1],"T":[-150,0,0]}})";

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto pos = s.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  if (pos != std::string::npos) s.replace(pos, from.size(), to);
  return s;
}

TEST(CalibJson, ParsesTheContract) {
  auto rig = parse_calib_json(kGood);
  ASSERT_TRUE(rig.ok()) << rig.error().message;
  EXPECT_EQ(rig->left.width, 1024);
  EXPECT_DOUBLE_EQ(rig->left.f_mm, 3.8);
  EXPECT_DOUBLE_EQ(rig->right.sx, 1.001);
  EXPECT_DOUBLE_EQ(rig->right.T_mm.x(), -150.0);
  EXPECT_DOUBLE_EQ(rig->left.kappa1, -0.004);
}

TEST(CalibJson, FormatThenParseIsExact) {
  auto rig = parse_calib_json(kGood);
  ASSERT_TRUE(rig.ok());
  rig->right.R =
      Eigen::Matrix3d(Eigen::AngleAxisd(0.1234567891, Eigen::Vector3d(1, 2, 3).normalized()));
  std::array<char, 2048> buf;
  auto n = format_calib_json(*rig, buf);
  ASSERT_TRUE(n.ok()) << n.error().message;
  auto again = parse_calib_json(std::string_view(buf.data(), *n));
  ASSERT_TRUE(again.ok()) << again.error().message;
  EXPECT_EQ(again->right.R, rig->right.R);
  EXPECT_EQ(again->left.cx_px, rig->left.cx_px);
  EXPECT_EQ(again->right.kappa1, rig->right.kappa1);
}

struct BadCase {
  std::string from, to;
  Errc code;
  const char* names;  // the message must name the field
};

TEST(CalibJson, EveryLoaderErrorNamesTheField) {
  const BadCase cases[] = {
      {R"("f":3.8,)", "", Errc::missing_field, "left.f"},
      {R"("f":3.81,)", R"("f":"x",)", Errc::wrong_type, "right.f"},
      {R"("f":3.8,)", R"("f":0,)", Errc::non_positive, "left.f"},
      {R"("f":3.8,)", R"("f":-2,)", Errc::non_positive, "left.f"},
      {R"("dx":0.00465,"dy":0.00465,"R":[1,0,0,0,1,0,0,0,1],"T":[0,0,0])",
       R"("dx":0,"dy":0.00465,"R":[1,0,0,0,1,0,0,0,1],"T":[0,0,0])", Errc::non_positive, "left.dx"},
      {R"("R":[1,0,0,0,1,0,0,0,1],"T":[0,0,0])", R"("R":[1,0.2,0,0,1,0,0,0,1],"T":[0,0,0])",
       Errc::not_orthonormal, "left.R"},
      {R"("R":[1,0,0,0,1,0,0,0,1],"T":[-150)", R"("R":[1,0,0,0,1,0,0,0,-1],"T":[-150)",
       Errc::not_orthonormal, "right.R"},
      {R"("R":[1,0,0,0,1,0,0,0,1],"T":[0,0,0])", R"("R":[1,0,0,0,1,0,0,0],"T":[0,0,0])",
       Errc::wrong_type, "left.R"},
      {R"("T":[0,0,0])", R"("T":[0,"a",0])", Errc::wrong_type, "left.T"},
      {R"("T":[0,0,0])", R"("X":[0,0,0])", Errc::missing_field, "left.T"},
      {R"("width":1024,"height":768,"f":3.8)", R"("width":10.5,"height":768,"f":3.8)",
       Errc::invalid_argument, "left.width"},
      {R"("kappa1":-0.004)", R"("kappa1":-0.5)", Errc::invalid_argument, "left.kappa1"},
      {R"("model":"tsai-rac")", R"("model":"pinhole")", Errc::invalid_argument, "model"},
      {R"("units":"mm",)", "", Errc::missing_field, "units"},
      {R"("right":{)", R"("rite":{)", Errc::missing_field, "right"},
      {R"("T":[-150,0,0]}})", R"("T":[-150,0,0]})", Errc::parse_error, "json"},
  };
  for (const BadCase& c : cases) {
    const std::string text = replace(kGood, c.from, c.to);
    auto rig = parse_calib_json(text);
    ASSERT_FALSE(rig.ok()) << c.names;
    EXPECT_EQ(rig.code(), c.code) << c.names << ": " << rig.error().message;
    EXPECT_NE(std::strstr(rig.error().message, c.names), nullptr) << rig.error().message;
  }
}

TEST(CalibJson, RejectsNonObjectAndEmpty) {
  EXPECT_FALSE(parse_calib_json("").ok());
  EXPECT_FALSE(parse_calib_json("[]").ok());
  EXPECT_FALSE(parse_calib_json("{}").ok());
}

TEST(CalibJson, ParsesWithoutHeap) {
  test::HeapScope scope;
  for (int i = 0; i < 50; ++i) ASSERT_TRUE(parse_calib_json(kGood).ok());
  EXPECT_EQ(scope.allocations(), 0u);
}

}  // namespace
}  // namespace petra

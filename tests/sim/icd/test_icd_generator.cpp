// docs/icd.md (packet section) and docs/petra.xtce.xml are what the packet
// definitions generate today: regenerate and compare, so they cannot drift.
#include "sim/icd/icd_generator.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "cmd/commands.hpp"
#include "tlm/telemetry.hpp"

namespace petra::icd {
namespace {

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

const std::string kDocs = std::string(PETRA_SOURCE_DIR) + "/docs";

TEST(IcdGenerator, IcdMarkdownMatchesThePacketDefinitions) {
  const std::string doc = slurp(kDocs + "/icd.md");
  ASSERT_FALSE(extract_section(doc).empty()) << "docs/icd.md has no generated packet section";
  EXPECT_EQ(extract_section(doc), markdown_section())
      << "docs/icd.md is out of date: run `petra icd` from the repository root";
}

TEST(IcdGenerator, XtceMatchesThePacketDefinitions) {
  EXPECT_EQ(slurp(kDocs + "/petra.xtce.xml"), xtce_document())
      << "docs/petra.xtce.xml is out of date: run `petra icd` from the repository root";
}

TEST(IcdGenerator, EveryCommandAndTelemetryFieldIsDocumented) {
  const std::string md = markdown_section();
  const std::string xtce = xtce_document();
  for (const auto& c : cmd::command_table()) {
    EXPECT_NE(md.find(std::string("#### ") + c.name + " "), std::string::npos) << c.name;
    EXPECT_NE(xtce.find(std::string("<xtce:MetaCommand name=\"") + c.name + "\""),
              std::string::npos);
    for (const auto& f : c.fields)
      EXPECT_NE(md.find(std::string("`") + f.name + "`"), std::string::npos);
  }
  for (const auto& t : tlm::telemetry_table()) {
    EXPECT_NE(md.find(std::string("#### ") + t.name + " "), std::string::npos) << t.name;
    for (const auto& f : t.fields)
      EXPECT_NE(xtce.find(std::string("name=\"") + t.name + "." + f.name + "\""),
                std::string::npos);
  }
}

TEST(IcdGenerator, SpliceReplacesOnlyTheGeneratedSection) {
  const std::string doc = "# ICD\n\nhand text\n\n" + std::string(kBeginMarker) + "\nold\n" +
                          kEndMarker + "\n\n## later section\n";
  const std::string out = splice_section(doc, markdown_section());
  EXPECT_EQ(out.find("old\n"), std::string::npos);
  EXPECT_NE(out.find("hand text"), std::string::npos);
  EXPECT_NE(out.find("## later section"), std::string::npos);
  EXPECT_EQ(extract_section(out), markdown_section());
}

TEST(IcdGenerator, XtceIsWellFormedXml) {
  if (std::system("command -v xmllint >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "xmllint not installed";
  EXPECT_EQ(std::system(("xmllint --noout " + kDocs + "/petra.xtce.xml").c_str()), 0);
}

}  // namespace
}  // namespace petra::icd

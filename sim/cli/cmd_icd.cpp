// `petra icd [--docs DIR] [--check]`: regenerates the packet section of
// docs/icd.md and docs/petra.xtce.xml from the packet definitions; --check
// only compares and fails when either is out of date.
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "sim/cli/commands.hpp"
#include "sim/icd/icd_generator.hpp"

namespace petra::cli {

namespace {
std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}
}  // namespace

void add_icd(CLI::App& app, Outcome& outcome) {
  auto* sub = app.add_subcommand(
      "icd", "Regenerate (or --check) docs/icd.md packets and docs/petra.xtce.xml");
  static std::string docs = "docs";
  static bool check = false;
  sub->add_option("--docs", docs, "docs folder")->capture_default_str();
  sub->add_flag("--check", check, "compare only; exit 1 when out of date");
  sub->callback([&outcome] {
    const std::string md_path = docs + "/icd.md";
    const std::string xtce_path = docs + "/petra.xtce.xml";
    const std::string md = slurp(md_path);
    const std::string new_md = icd::splice_section(md, icd::markdown_section());
    const std::string xtce = icd::xtce_document();
    if (check) {
      const bool md_ok = new_md == md;
      const bool xtce_ok = slurp(xtce_path) == xtce;
      if (!md_ok) std::fprintf(stderr, "petra icd: %s is out of date\n", md_path.c_str());
      if (!xtce_ok) std::fprintf(stderr, "petra icd: %s is out of date\n", xtce_path.c_str());
      outcome.exit_code = md_ok && xtce_ok ? 0 : 1;
      if (outcome.exit_code == 0)
        std::printf("%s and %s match the packet definitions\n", md_path.c_str(), xtce_path.c_str());
      return;
    }
    std::ofstream(md_path, std::ios::trunc) << new_md;
    std::ofstream(xtce_path, std::ios::trunc) << xtce;
    std::printf("wrote %s (packet section) and %s\n", md_path.c_str(), xtce_path.c_str());
  });
}

}  // namespace petra::cli

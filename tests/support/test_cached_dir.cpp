// cached_dir: made once, made again when the key changes or the program that
// made it is newer, and a failed make leaves no copy.
#include "tests/support/cached_dir.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

namespace petra::test {
namespace {

namespace fs = std::filesystem;

// A name of this process's own, so parallel test processes do not share it.
std::string unique_name(const char* what) {
  return std::string("cached_dir_test_") + what + "_" + std::to_string(::getpid());
}

void remove_cached(const std::string& name) {
  const fs::path root = PETRA_TEST_CACHE_DIR;
  fs::remove_all(root / name);
  fs::remove(root / (name + ".lock"));
}

TEST(CachedDir, MadeOnceThenReusedUntilTheKeyChanges) {
  const std::string name = unique_name("key");
  int makes = 0;
  const auto make = [&](const fs::path& out) {
    ++makes;
    std::ofstream(out / "file") << makes;
    return true;
  };
  const fs::path a = cached_dir(name, "key 1", this_executable(), make);
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(cached_dir(name, "key 1", this_executable(), make), a);
  EXPECT_EQ(makes, 1);
  EXPECT_EQ(cached_dir(name, "key 2", this_executable(), make), a);
  EXPECT_EQ(makes, 2);
  std::string content;
  std::ifstream(a / "file") >> content;
  EXPECT_EQ(content, "2");
  remove_cached(name);
}

TEST(CachedDir, ANewerProgramMakesItAgain) {
  const std::string name = unique_name("newer");
  int makes = 0;
  const auto make = [&](const fs::path&) { return ++makes > 0; };
  const fs::path program = fs::path(PETRA_TEST_CACHE_DIR) / (name + ".program");
  const fs::path dir = cached_dir(name, "k", this_executable(), make);
  ASSERT_FALSE(dir.empty());
  std::ofstream(program) << "rebuilt";
  fs::last_write_time(program, fs::last_write_time(dir / ".cache_key") + std::chrono::seconds(5));
  cached_dir(name, "k", program, make);
  EXPECT_EQ(makes, 2);
  remove_cached(name);
  fs::remove(program);
}

TEST(CachedDir, AFailedMakeLeavesNoCopy) {
  const std::string name = unique_name("failed");
  const auto fail = [](const fs::path& out) {
    std::ofstream(out / "half") << "written before the failure";
    return false;
  };
  EXPECT_TRUE(cached_dir(name, "k", this_executable(), fail).empty());
  EXPECT_FALSE(fs::exists(fs::path(PETRA_TEST_CACHE_DIR) / name));
  EXPECT_FALSE(fs::exists(fs::path(PETRA_TEST_CACHE_DIR) / (name + ".tmp")));
  remove_cached(name);
}

}  // namespace
}  // namespace petra::test

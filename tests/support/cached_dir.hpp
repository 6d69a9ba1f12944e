// A directory of test inputs made once per build tree and shared by the test
// processes that read it. ctest runs every test case in its own process, so a
// suite fixture that renders a scene (~15 s under the sanitizers) would render
// it again for each case; cached_dir makes it once:
//
//   const fs::path dir = petra::test::cached_dir("scene_seed3", "sim scene --seed 3",
//       PETRA_CLI_BIN, [](const fs::path& out) { return render_into(out); });
//
// The directory is made again when its key changes or when `made_by` (the
// program that makes it) is newer than the copy. A lock file serialises the
// processes; the copy appears only once complete (made in a temporary
// directory, then renamed), so a failed or interrupted make leaves no copy.
// Readers must not write into the directory.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace petra::test {

// Returns PETRA_TEST_CACHE_DIR/name, or an empty path when make() failed.
std::filesystem::path cached_dir(const std::string& name, const std::string& key,
                                 const std::filesystem::path& made_by,
                                 const std::function<bool(const std::filesystem::path&)>& make);

// cached_dir for `petra <petra_args> --out DIR`, made by the petra binary.
std::filesystem::path cached_petra_output(const std::string& name, const std::string& petra_bin,
                                          const std::string& petra_args);

// This test executable's own path: the `made_by` of what it makes in process.
std::filesystem::path this_executable();

}  // namespace petra::test

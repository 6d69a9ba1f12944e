// The command counter file under power cuts. A simulated file system keeps,
// for each file and for the folder, what is durable (fsync'd) apart from what
// is only in the page cache; a power cut before any file call keeps, in the
// worst combinations, the durable or the cached names and the durable or the
// cached data. After every such cut the restarted store must read a counter at
// least as high as every counter store() confirmed: no replay window.
#include "cmd/counter_store.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "tests/support/heap_counter.hpp"

namespace petra::test {
namespace {

class PowerCutFs : public cmd::FileOps {
 public:
  struct Inode {
    std::string data;     // as the process sees it
    std::string durable;  // what survives a power cut for sure
  };
  std::map<std::string, int> names, durable_names;  // one folder, "/fs"
  std::vector<Inode> inodes;
  int cut_at = -1;  // the call the power is cut before (-1: never)
  int calls = 0;
  bool dead = false;
  bool fsync_works = true;  // false: a writer (or disk) whose fsync keeps nothing

  void put_durable(const std::string& name, const std::string& data) {
    inodes.push_back({data, data});
    names[name] = durable_names[name] = static_cast<int>(inodes.size()) - 1;
  }
  // The file system after the cut, with the cached (true) or durable names and data.
  PowerCutFs after_cut(bool cached_names, bool cached_data) const {
    PowerCutFs fs;
    fs.inodes = inodes;
    for (Inode& i : fs.inodes) i.durable = i.data = cached_data ? i.data : i.durable;
    fs.names = fs.durable_names = cached_names ? names : durable_names;
    return fs;
  }

  int open(const char* path, int flags, int) override {
    if (!step()) return -1;
    const std::string p = path;
    if ((flags & O_DIRECTORY) != 0) return p == "/fs" ? kDirFd : fail(ENOENT);
    auto it = names.find(p);
    if (it == names.end()) {
      if ((flags & O_CREAT) == 0) return fail(ENOENT);
      inodes.push_back({});
      it = names.emplace(p, static_cast<int>(inodes.size()) - 1).first;
    } else if ((flags & O_TRUNC) != 0) {
      inodes[static_cast<std::size_t>(it->second)].data.clear();
    }
    return kFirstFd + it->second;
  }
  ssize_t pread(int fd, void* buf, std::size_t n, off_t at) override {
    if (!step()) return -1;
    const std::string& d = inode(fd).data;
    const std::size_t from = std::min(d.size(), static_cast<std::size_t>(at));
    const std::size_t k = std::min(n, d.size() - from);
    std::memcpy(buf, d.data() + from, k);
    return static_cast<ssize_t>(k);
  }
  ssize_t write(int fd, const void* buf, std::size_t n) override {
    if (!step()) return -1;
    inode(fd).data.append(static_cast<const char*>(buf), n);
    return static_cast<ssize_t>(n);
  }
  int fsync(int fd) override {
    if (!step()) return -1;
    if (!fsync_works) return 0;
    if (fd == kDirFd)
      durable_names = names;
    else
      inode(fd).durable = inode(fd).data;
    return 0;
  }
  int close(int) override { return step() ? 0 : -1; }
  int rename(const char* from, const char* to) override {
    if (!step()) return -1;
    auto it = names.find(from);
    if (it == names.end()) return fail(ENOENT);
    names[to] = it->second;
    names.erase(from);
    return 0;
  }

 private:
  static constexpr int kDirFd = 3;
  static constexpr int kFirstFd = 10;
  bool step() {
    if (cut_at >= 0 && calls++ >= cut_at) dead = true;
    if (dead) errno = EIO;
    return !dead;
  }
  static int fail(int e) {
    errno = e;
    return -1;
  }
  Inode& inode(int fd) { return inodes[static_cast<std::size_t>(fd - kFirstFd)]; }
};

const char* kPath = "/fs/counter";
const cmd::KeyId kKey{1, 2, 3, 4, 5, 6, 7, 8};

std::string line(std::uint32_t counter) {
  char text[40];
  (void)std::snprintf(text, sizeof(text), "%010u 0102030405060708\n", counter);
  return text;
}

struct CutResult {
  bool cut = false;            // the power was cut before the updates ended
  std::uint32_t accepted = 0;  // the last counter store() confirmed
  int replays = 0;             // restarts that read a counter below it
  int unreadable = 0;          // restarts that found no valid counter
};

// Three updates (6, 7, 8) after 5, the power cut before call number `cut_at`.
CutResult run_with_cut(int cut_at, bool fsync_works) {
  PowerCutFs fs;
  fs.put_durable(kPath, line(5));
  fs.fsync_works = fsync_works;
  fs.cut_at = cut_at;
  cmd::CounterStore store;
  EXPECT_TRUE(store.bind(kPath, kKey, &fs).ok());
  CutResult r;
  r.accepted = 5;
  for (std::uint32_t c = 6; c <= 8; ++c) {
    if (!store.store(c).ok()) break;
    r.accepted = c;  // confirmed: the command it admits may now run
  }
  r.cut = fs.dead;
  for (const bool cached_names : {false, true})
    for (const bool cached_data : {false, true}) {
      PowerCutFs restarted = fs.after_cut(cached_names, cached_data);
      cmd::CounterStore again;
      EXPECT_TRUE(again.bind(kPath, kKey, &restarted).ok());
      auto got = again.load();
      if (!got.ok() || !got->exists || !got->same_key)
        ++r.unreadable;
      else if (got->counter < r.accepted)
        ++r.replays;
      else
        EXPECT_LE(got->counter, r.accepted + 1) << "cut before call " << cut_at;
    }
  return r;
}

TEST(CounterStore, APowerCutAtEveryStepNeverLetsAnAcceptedCounterBack) {
  int cuts = 0;
  for (int cut_at = 0;; ++cut_at) {
    SCOPED_TRACE("power cut before file call " + std::to_string(cut_at));
    const CutResult r = run_with_cut(cut_at, true);
    if (!r.cut) break;  // past the last call of the three updates
    ++cuts;
    EXPECT_EQ(r.replays, 0);
    EXPECT_EQ(r.unreadable, 0);
  }
  EXPECT_EQ(cuts,
            3 * 8);  // 8 calls per update: open, write, fsync, close, rename, open, fsync, close
}

TEST(CounterStore, TheCrashModelCatchesAWriterWhoseFsyncKeepsNothing) {
  // The control: the same cuts with fsync doing nothing open replay windows.
  int replays = 0;
  for (int cut_at = 0; cut_at < 3 * 8; ++cut_at) replays += run_with_cut(cut_at, false).replays;
  EXPECT_GT(replays, 0);
}

TEST(CounterStore, ReadsItsOwnFilesOlderFilesAndTellsAnotherKeys) {
  PowerCutFs fs;
  cmd::CounterStore store;
  ASSERT_TRUE(store.bind(kPath, kKey, &fs).ok());
  auto none = store.load();
  ASSERT_TRUE(none.ok());
  EXPECT_FALSE(none->exists);
  ASSERT_TRUE(store.store(4294967295u).ok());
  auto full = store.load();
  ASSERT_TRUE(full.ok());
  EXPECT_EQ(full->counter, 4294967295u);
  EXPECT_TRUE(full->same_key);
  fs.put_durable(kPath, "0000000042\n");  // written by an older release: no key id
  auto old = store.load();
  ASSERT_TRUE(old.ok());
  EXPECT_EQ(old->counter, 42u);
  EXPECT_TRUE(old->same_key);
  fs.put_durable(kPath, "0000000042 0102030405060709\n");
  auto other = store.load();
  ASSERT_TRUE(other.ok());
  EXPECT_FALSE(other->same_key);
  for (const char* bad : {"", "\n", "42", "x\n", "4294967296\n", "0000000042 01020304\n",
                          "0000000042 01020304050607zz\n", "0000000042 0102030405060708"}) {
    fs.put_durable(kPath, bad);
    auto r = store.load();
    ASSERT_FALSE(r.ok()) << '"' << bad << '"';
    EXPECT_EQ(r.code(), Errc::parse_error);
    EXPECT_NE(std::string(r.error().message).find(kPath), std::string::npos);
  }
}

TEST(CounterStore, StoringOnARealFolderAllocatesNothing) {
  const std::string dir = ::testing::TempDir() + "petra_counter_" + std::to_string(::getpid());
  ASSERT_EQ(::mkdir(dir.c_str(), 0700), 0);
  const std::string path = dir + "/fsw-counter";
  cmd::CounterStore store;
  ASSERT_TRUE(store.bind(path.c_str(), kKey).ok());
  ASSERT_TRUE(store.store(1).ok());
  if (counts_malloc()) {
    HeapScope heap;
    for (std::uint32_t c = 2; c < 20; ++c) ASSERT_TRUE(store.store(c).ok());
    EXPECT_EQ(heap.allocations(), 0u);
  }
  auto got = store.load();
  ASSERT_TRUE(got.ok());
  EXPECT_EQ(got->counter, counts_malloc() ? 19u : 1u);
  struct stat st {};
  ASSERT_EQ(::stat(path.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  std::remove(path.c_str());
  ::rmdir(dir.c_str());
}

}  // namespace
}  // namespace petra::test

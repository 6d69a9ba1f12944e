// Whether this process can start a thread. qemu-aarch64-static (the aarch64
// unit-test runner) hangs in thread creation on some host kernels; tests that
// need a second thread ask first, in a child process with a time limit, and
// skip saying why. The host build and the HIL guest run them.
#pragma once

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>

namespace petra::test {

inline bool threads_usable() {
  static const bool usable = [] {
    const pid_t child = ::fork();
    if (child < 0) return false;
    if (child == 0) {
      std::thread t([] {});
      t.join();
      ::_exit(0);
    }
    for (int i = 0; i < 300; ++i) {  // 3 s
      int status = 0;
      if (::waitpid(child, &status, WNOHANG) == child)
        return WIFEXITED(status) && WEXITSTATUS(status) == 0;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ::kill(child, SIGKILL);
    ::waitpid(child, nullptr, 0);
    return false;
  }();
  return usable;
}

}  // namespace petra::test

#define PETRA_REQUIRE_THREADS()                                                          \
  do {                                                                                   \
    if (!::petra::test::threads_usable())                                                \
      GTEST_SKIP() << "skipped: this emulator cannot start threads (the host build and " \
                      "the HIL guest run this test)";                                    \
  } while (false)

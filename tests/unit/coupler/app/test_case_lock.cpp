// CaseLock: one run of a case at a time; the lock files go when the run ends.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "coupler/app/case_lock.hpp"
#include "tests/support/temporary_directory.hpp"

namespace cocopp {
namespace {

TEST(CaseLock, IsTakenOnceAndItsFilesGoWhenReleased) {
  testing::TemporaryDirectory directory;
  const auto results = directory.path() / "results" / "case.lock";
  const auto solver = directory.path() / "flow" / ".cocopp.lock";
  {
    const CaseLock lock({results, solver});
    EXPECT_TRUE(std::filesystem::exists(results));
    // Another process cannot take it, and learns who holds it.
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      try {
        CaseLock second({results});
      } catch (const std::runtime_error& e) {
        const std::string pid = "(pid " + std::to_string(::getppid()) + ")";
        ::_exit(std::string(e.what()).find(pid) != std::string::npos ? 3 : 4);
      }
      ::_exit(5);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    EXPECT_EQ(WEXITSTATUS(status), 3) << "3: refused, naming this process";
  }
  EXPECT_FALSE(std::filesystem::exists(results));
  EXPECT_FALSE(std::filesystem::exists(solver));
  // A file a killed run left behind (unlocked) is taken over.
  std::filesystem::create_directories(results.parent_path());
  { std::ofstream(results) << "12345\n"; }
  EXPECT_NO_THROW(CaseLock({results}));
  EXPECT_FALSE(std::filesystem::exists(results));
}

}  // namespace
}  // namespace cocopp

// Issue 17, defect 9: paths that cannot be used are described in words (std::filesystem's
// throwing calls said "filesystem error: status: Too many levels of symbolic links [...]").
#include <gtest/gtest.h>

#include <fstream>

#include "core/case/path_problem.hpp"
#include "tests/support/temporary_directory.hpp"

namespace fs = std::filesystem;
using cocopp::path_problem;
using cocopp::PathKind;

TEST(PathProblem, ADirectoryAndAFileThatCanBeUsedHaveNone) {
  cocopp::testing::TemporaryDirectory dir;
  cocopp::testing::write_text(dir / "file", "x\n");
  EXPECT_EQ(path_problem(dir.path(), PathKind::kDirectory), "");
  EXPECT_EQ(path_problem(dir / "file", PathKind::kRegularFile), "");
  EXPECT_EQ(path_problem(dir / "file", PathKind::kAny), "");
}

TEST(PathProblem, EachProblemIsNamed) {
  cocopp::testing::TemporaryDirectory dir;
  cocopp::testing::write_text(dir / "file", "x\n");
  fs::create_symlink("loop_b", dir / "loop_a");
  fs::create_symlink("loop_a", dir / "loop_b");
  EXPECT_EQ(path_problem(dir / "missing", PathKind::kAny), "does not exist");
  EXPECT_EQ(path_problem(dir / "file", PathKind::kDirectory), "is not a directory");
  EXPECT_EQ(path_problem(dir.path(), PathKind::kRegularFile), "is a directory, not a file");
  EXPECT_NE(path_problem(dir / "loop_a", PathKind::kDirectory).find("loop of symbolic links"),
            std::string::npos);
  EXPECT_NE(path_problem(dir / "loop_a" / "below", PathKind::kAny).find("loop of symbolic links"),
            std::string::npos);
  EXPECT_NE(path_problem(dir / std::string(300, 'x'), PathKind::kDirectory)
                .find("has a name longer than the file system allows"),
            std::string::npos);
  EXPECT_NE(path_problem(dir / "file" / "below", PathKind::kAny).find("does not exist"),
            std::string::npos);
}

TEST(PathProblem, AThrownFilesystemErrorIsDescribedWithItsPath) {
  cocopp::testing::TemporaryDirectory dir;
  fs::create_symlink("loop_b", dir / "loop_a");
  fs::create_symlink("loop_a", dir / "loop_b");
  try {
    (void)fs::is_directory(dir / "loop_a");
    FAIL() << "no filesystem error";
  } catch (const fs::filesystem_error& e) {
    EXPECT_EQ(
        cocopp::describe_filesystem_error(e),
        (dir / "loop_a").string() + " is a loop of symbolic links (or more than 40 links deep)");
  }
}

TEST(PathProblem, ADirectoryToCreateNeedsAWritableFolderAboveIt) {
  cocopp::testing::TemporaryDirectory dir;
  EXPECT_EQ(cocopp::creation_problem(dir.path()), "");              // exists
  EXPECT_EQ(cocopp::creation_problem(dir / "new" / "deeper"), "");  // can be made
  { std::ofstream(dir / "file") << "x"; }
  EXPECT_EQ(cocopp::creation_problem(dir / "file"), "is not a directory");
  EXPECT_EQ(cocopp::creation_problem(dir / "file" / "results"),
            "does not exist (a part of it is a file)");
}

#pragma once
// Running a shell command of a test (making a case, blockMesh, a script) in a directory, with
// its output in log.setup there: a failure fails the test with that log.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "tests/support/temporary_directory.hpp"

namespace cocopp::testing {

inline void run_in(const std::filesystem::path& directory, const std::string& command) {
  const std::string line = "cd '" + directory.string() +
                           "' && WM_PROJECT_DIR=/usr/share/openfoam " + command +
                           " >> log.setup 2>&1";
  ASSERT_EQ(std::system(line.c_str()), 0) << line << "\n" << read_text(directory / "log.setup");
}

}  // namespace cocopp::testing

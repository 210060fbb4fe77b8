#pragma once
// A hint for a Python solver that died for want of a module: which interpreter its command
// ran (a `python3` found on PATH may not be the one with NumPy), and how to choose another or
// find cocopp_sdk (docs/python.md, "Python solvers").
#include <filesystem>
#include <string>
#include <vector>

namespace cocopp {

/// "" unless `log_tail` holds Python's "No module named 'X'"; then a line naming the
/// interpreter `command` ran (`interpreter`: command[0] as it was found), and what to change.
/// `sdk_directory`: where this cocopp installed cocopp_sdk.py ("" if not known).
std::string python_module_hint(const std::vector<std::string>& command,
                               const std::filesystem::path& interpreter,
                               const std::string& log_tail,
                               const std::filesystem::path& sdk_directory);

/// Where the cocopp_sdk.py of this cocopp is: <prefix>/lib/python3/dist-packages next to the
/// running executable's <prefix>/bin; "" if it is not there (a build tree).
std::filesystem::path installed_python_sdk_directory();

}  // namespace cocopp

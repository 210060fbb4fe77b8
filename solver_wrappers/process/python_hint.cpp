#include "solver_wrappers/process/python_hint.hpp"

#include <fmt/format.h>

#include <regex>
#include <system_error>

namespace cocopp {

std::string python_module_hint(const std::vector<std::string>& command,
                               const std::filesystem::path& interpreter,
                               const std::string& log_tail,
                               const std::filesystem::path& sdk_directory) {
  static const std::regex missing(R"(No module named '([A-Za-z0-9_.]+)')");
  std::smatch match;
  if (command.empty() || !std::regex_search(log_tail, match, missing)) return "";
  const std::string module = match[1];
  std::error_code error;
  const auto resolved = std::filesystem::canonical(interpreter, error);
  const std::string ran = command[0] == interpreter.string()
                              ? command[0]
                              : fmt::format("{} (found as {})", command[0], interpreter.string());
  std::string hint = fmt::format(
      "hint: the solver's command ran {}{}, which has no module '{}'.", ran,
      !error && resolved != interpreter ? ", that is " + resolved.string() : "", module);
  if (module == "cocopp_sdk") {
    hint += sdk_directory.empty()
                ? " cocopp_sdk.py is installed in <prefix>/lib/python3/dist-packages of the "
                  "cocopp install (in a build tree: solvers/sdk/ of the sources): put that "
                  "folder on PYTHONPATH."
                : fmt::format(
                      " This cocopp's cocopp_sdk.py is in {}: put it on PYTHONPATH "
                      "(export PYTHONPATH={}).",
                      sdk_directory.string(), sdk_directory.string());
  } else {
    hint += fmt::format(
        " Name an interpreter that has it in the solver wrapper's command (command: "
        "[/usr/bin/python3, ...] is Debian's, where its package python3-{} installs), or "
        "install '{}' for {}.",
        module, module, command[0]);
  }
  return hint;
}

std::filesystem::path installed_python_sdk_directory() {
  std::error_code error;
  const auto executable = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) return {};
  const auto directory =
      executable.parent_path().parent_path() / "lib" / "python3" / "dist-packages";
  return std::filesystem::exists(directory / "cocopp_sdk.py", error) ? directory
                                                                     : std::filesystem::path();
}

}  // namespace cocopp

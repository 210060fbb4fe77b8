#include "coupler/app/plot.hpp"

#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>

namespace cocopp {

namespace fs = std::filesystem;

namespace {

constexpr const char* kPython = "/usr/bin/python3";

/// The script that draws `file`, "" for a kind no script draws.
std::string script_for(const fs::path& file) {
  if (file.extension() == ".h5") return "plot_results.py";
  if (file.extension() == ".json" && file.stem() == "bench") return "plot_bench.py";
  return "";
}

}  // namespace

namespace {

/// <prefix>: above the running executable's bin/.
fs::path installation_prefix() {
  std::error_code error;
  return fs::read_symlink("/proc/self/exe", error).parent_path().parent_path();
}

}  // namespace

fs::path shared_script(const std::string& name) {
  return installation_prefix() / "share" / "cocopp" / name;
}

std::string documentation(const std::string& page) {
  return (installation_prefix() / "share" / "doc" / "cocopp" / page).string();
}

int plot_file(const fs::path& file, const std::vector<std::string>& arguments) {
  const std::string script = script_for(file);
  if (script.empty()) {
    fmt::print(stderr,
               "error: {}: cocopp plot draws a results file (<name>.h5, plot_results.py) or a "
               "bench's bench.json (plot_bench.py)\n",
               file.string());
    return 2;
  }
  std::vector<std::string> words = {kPython, shared_script(script).string(), file.string()};
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (auto& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);
  const pid_t child = ::fork();
  if (child == 0) {
    ::execv(kPython, argv.data());
    fmt::print(stderr, "error: cannot start {}: {}\n", kPython, std::strerror(errno));
    ::_exit(127);
  }
  int status = 0;
  if (child < 0 || ::waitpid(child, &status, 0) < 0) {
    fmt::print(stderr, "error: cannot run {}: {}\n", kPython, std::strerror(errno));
    return 1;
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status) == 127 ? 1 : WEXITSTATUS(status);
  return 1;
}

}  // namespace cocopp

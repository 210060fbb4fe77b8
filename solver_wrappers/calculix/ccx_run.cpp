#include "solver_wrappers/calculix/ccx_run.hpp"

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "solver_wrappers/process/child_process.hpp"

namespace cocopp::calculix {

namespace {

constexpr std::size_t kLogTailLines = 20;
constexpr double kStopGraceSeconds = 1.0;
constexpr std::size_t kMaxErrorMessages = 10;

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

CcxRestartSupport restart_support(const std::filesystem::path& executable,
                                  const std::filesystem::path& scratch_directory) {
  ChildOptions options;
  options.command = {executable.string(), "-v"};
  options.working_directory = scratch_directory;
  options.log_file = scratch_directory / "cocopp_ccx_version.log";
  options.truncate_log = true;
  std::string version;
  try {
    version = run_to_end(options, 10.0).output;
  } catch (const std::runtime_error&) {
    return {};
  }
  // The version line the patches print (01-..., 02-restart-axisymmetry.patch, 07-warm-start).
  const auto says = [&](const char* text) { return version.find(text) != std::string::npos; };
  return {says("cocopp: restart files keep the state variables"),
          says("cocopp: restart files keep the state variables and the axisymmetry flag"),
          says("; warm start)")};
}

std::string error_messages(const std::string& log_text) {
  std::istringstream lines(log_text);
  std::string line;
  std::string messages;
  std::size_t count = 0;
  bool inside = false;
  while (std::getline(lines, line)) {
    const bool blank = line.find_first_not_of(" \t\r") == std::string::npos;
    if (line.find("*ERROR") != std::string::npos) {
      // "*ERROR in calinput: at least one fatal error" only says that there were errors.
      if (line.find("*ERROR in calinput") != std::string::npos) continue;
      inside = ++count <= kMaxErrorMessages;
    } else if (blank) {
      inside = false;
    }
    if (inside) messages += line + "\n";
  }
  if (count > kMaxErrorMessages)
    messages += "(" + std::to_string(count - kMaxErrorMessages) + " more *ERROR messages)\n";
  return messages;
}

bool gave_up(const std::string& log_text) {
  return log_text.find("increment size smaller than minimum") != std::string::npos ||
         log_text.find("too many cutbacks") != std::string::npos ||
         log_text.find("max. # of increments reached") != std::string::npos;
}

// A ccx run allocates (and zeroes) its arrays anew: the wire drawing case's took 67 000 page
// faults, a fifth of a warm-started run's time on a virtual machine. glibc's malloc asks for
// transparent huge pages where the kernel gives them on request (`madvise`, Debian's
// default): 13 000 faults, the same results (docs/solver-wrappers-calculix.md).
static std::string huge_page_tunables() {
  const char* given = std::getenv("GLIBC_TUNABLES");
  const std::string tunable = "glibc.malloc.hugetlb=1";
  return given && *given ? std::string(given) + ":" + tunable : tunable;
}

std::vector<std::pair<std::string, std::string>> ccx_thread_environment(int threads) {
  const std::string count = std::to_string(threads);
  // ccx's own threads are pthreads (CCX_NPROC_*). Its libraries' are not theirs to multiply:
  // Debian's CHOLMOD opens OpenMP regions of a built-in 4 threads per supernode and OpenBLAS
  // one per core, which on top of ccx's oversubscribe the machine and spend a third of the
  // run waking and yielding threads (wire drawing, one coupling iteration of step 100 on
  // 2 cores: 6.2 s; 3.8 s with both limited to one, the same displacements to every digit
  // ccx prints; docs/solver-wrappers-calculix.md).
  return {{"OMP_NUM_THREADS", count},
          {"OMP_THREAD_LIMIT", "1"},
          {"OPENBLAS_NUM_THREADS", "1"},
          {"CCX_NPROC_EQUATION_SOLVER", count},
          {"CCX_NPROC_RESULTS", count},
          {"CCX_NPROC_STIFFNESS", count},
          {"GLIBC_TUNABLES", huge_page_tunables()}};
}

CcxRunResult run_ccx(const CcxRunOptions& options) {
  ChildOptions child_options;
  child_options.command = {options.executable.string(), "-i", options.job};
  child_options.working_directory = options.working_directory;
  child_options.environment = ccx_thread_environment(options.threads);
  child_options.environment.insert(child_options.environment.end(), options.environment.begin(),
                                   options.environment.end());
  child_options.log_file = options.log_file;
  child_options.truncate_log = true;  // the log holds the last run: the one to explain

  const auto start = std::chrono::steady_clock::now();
  ChildProcess ccx(child_options);
  const bool exited = ccx.wait_for_exit(options.timeout);
  if (!exited) ccx.stop(kStopGraceSeconds);
  CcxRunResult result;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.exit_code = ccx.exit_code();
  result.exit_description = ccx.describe_exit();
  if (!exited) {
    result.status = CcxRunResult::Status::kTimedOut;
    result.details = read_last_lines(options.log_file, kLogTailLines);
    return result;
  }
  if (result.exit_code == 0) return result;
  const std::string log = read_text(options.log_file);
  if (gave_up(log)) {
    result.status = CcxRunResult::Status::kNotConverged;
    result.details = read_last_lines(options.log_file, kLogTailLines);
    return result;
  }
  result.details = error_messages(log);
  if (!result.details.empty() && result.exit_code >= 0) {
    result.status = CcxRunResult::Status::kDeckError;
    return result;
  }
  result.status = CcxRunResult::Status::kFailed;
  result.details = read_last_lines(options.log_file, kLogTailLines);
  return result;
}

}  // namespace cocopp::calculix

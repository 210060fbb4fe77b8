#include "solver_wrappers/process/child_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <thread>

#include "core/case/path_problem.hpp"

extern char** environ;

namespace cocopp {

namespace {

// Live children for kill_all_children(), which runs in a signal handler: fixed slots of
// lock-free atomics, so that neither registering nor killing allocates or locks.
constexpr std::size_t kMaxChildren = 256;
std::atomic<pid_t> g_live_children[kMaxChildren];
static_assert(std::atomic<pid_t>::is_always_lock_free);

void register_child(pid_t pid) {
  for (auto& slot : g_live_children) {
    pid_t empty = 0;
    if (slot.compare_exchange_strong(empty, pid)) return;
  }
  // All slots taken: the child still dies with the coupler through PR_SET_PDEATHSIG.
}

void unregister_child(pid_t pid) {
  for (auto& slot : g_live_children) {
    pid_t expected = pid;
    if (slot.compare_exchange_strong(expected, 0)) return;
  }
}

/// A null-terminated char* array for execve, built before fork: the child must not allocate.
class CStringArray {
 public:
  explicit CStringArray(std::vector<std::string> strings) : strings_(std::move(strings)) {
    for (auto& text : strings_) pointers_.push_back(text.data());
    pointers_.push_back(nullptr);
  }
  CStringArray(const CStringArray&) = delete;
  CStringArray& operator=(const CStringArray&) = delete;
  char* const* get() const { return pointers_.data(); }

 private:
  std::vector<std::string> strings_;
  std::vector<char*> pointers_;
};

std::vector<std::string> child_environment(
    const std::vector<std::pair<std::string, std::string>>& overrides) {
  std::vector<std::string> environment;
  for (char** entry = environ; entry != nullptr && *entry != nullptr; ++entry) {
    const std::string text = *entry;
    const std::string key = text.substr(0, text.find('='));
    const bool overridden = std::any_of(overrides.begin(), overrides.end(),
                                        [&](const auto& item) { return item.first == key; });
    if (!overridden) environment.push_back(text);
  }
  for (const auto& [key, value] : overrides) environment.push_back(key + "=" + value);
  return environment;
}

int open_log(const std::filesystem::path& log_file, bool truncate) {
  // O_NOFOLLOW: a link planted at the log's name must not make the solver write its target.
  const int flags =
      O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC | O_NOFOLLOW | (truncate ? O_TRUNC : 0);
  const int fd = ::open(log_file.c_str(), flags, 0644);
  if (fd < 0)
    throw std::runtime_error("cannot open the log file " + log_file.string() + ": " +
                             std::strerror(errno));
  return fd;
}

/// What the child reports through the close-on-exec pipe when it cannot exec.
struct StartFailure {
  enum Stage : int { kStdio, kChdir, kExec } stage;
  int error;
};

[[noreturn]] void report_start_failure(int report_fd, StartFailure::Stage stage) {
  const StartFailure failure{stage, errno};
  const ssize_t ignored = ::write(report_fd, &failure, sizeof failure);
  (void)ignored;
  ::_exit(127);
}

// Runs in the forked child: async-signal-safe calls only.
[[noreturn]] void become_child(const char* executable, char* const* argv, char* const* envp,
                               const char* working_directory, int log_fd, int report_fd,
                               pid_t coupler) {
  ::setpgid(0, 0);
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != coupler) ::_exit(127);  // the coupler died before prctl took effect
  // Ignored signals stay ignored across exec (the transports ignore SIGPIPE): reset them all.
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  for (int signal = 1; signal < NSIG; ++signal) ::sigaction(signal, &default_action, nullptr);
  sigset_t no_signals;
  sigemptyset(&no_signals);
  ::sigprocmask(SIG_SETMASK, &no_signals, nullptr);
#ifdef CLOSE_RANGE_CLOEXEC
  // Descriptors opened without O_CLOEXEC by other code must not leak into the solver.
  ::close_range(3, ~0U, CLOSE_RANGE_CLOEXEC);
#endif
  const int null_fd = ::open("/dev/null", O_RDONLY);
  if (null_fd < 0 || ::dup2(null_fd, STDIN_FILENO) < 0 || ::dup2(log_fd, STDOUT_FILENO) < 0 ||
      ::dup2(log_fd, STDERR_FILENO) < 0)
    report_start_failure(report_fd, StartFailure::kStdio);
  if (::chdir(working_directory) != 0) report_start_failure(report_fd, StartFailure::kChdir);
  ::execve(executable, argv, envp);
  report_start_failure(report_fd, StartFailure::kExec);
}

std::string start_failure_text(const StartFailure& failure, const std::string& executable,
                               const std::string& working_directory) {
  const std::string reason = std::strerror(failure.error);
  switch (failure.stage) {
    case StartFailure::kChdir:
      return "cannot start " + executable + ": cannot enter " + working_directory + ": " + reason;
    case StartFailure::kStdio:
      return "cannot start " + executable + ": cannot redirect its output: " + reason;
    case StartFailure::kExec:
      break;
  }
  return "cannot start " + executable + ": " + reason;
}

bool is_executable_file(const std::filesystem::path& path) {
  std::error_code error;
  return std::filesystem::is_regular_file(path, error) && ::access(path.c_str(), X_OK) == 0;
}

}  // namespace

ChildProcess::ChildProcess(const ChildOptions& options) {
  if (options.command.empty()) throw std::invalid_argument("cannot start a process: no command");
  if (const auto why = path_problem(options.working_directory, PathKind::kDirectory); !why.empty())
    throw std::runtime_error("cannot start " + options.command[0] + ": working directory " +
                             options.working_directory.string() + " " + why);
  // Everything the child needs is prepared here: after fork() it may not allocate.
  const std::string executable =
      find_executable(options.command[0], options.working_directory).string();
  const std::string working_directory = std::filesystem::absolute(options.working_directory);
  const CStringArray argv(options.command);
  const CStringArray envp(child_environment(options.environment));
  const int log_fd = open_log(options.log_file, options.truncate_log);
  int report[2];
  if (::pipe2(report, O_CLOEXEC) != 0) {
    ::close(log_fd);
    throw std::runtime_error("cannot start " + executable + ": pipe: " + std::strerror(errno));
  }

  const pid_t coupler = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0)
    become_child(executable.c_str(), argv.get(), envp.get(), working_directory.c_str(), log_fd,
                 report[1], coupler);
  const int fork_error = errno;
  ::close(report[1]);
  ::close(log_fd);
  if (pid < 0) {
    ::close(report[0]);
    throw std::runtime_error("cannot start " + executable + ": fork: " + std::strerror(fork_error));
  }
  ::setpgid(pid, pid);  // the child does the same: no window in which it has no group
  register_child(pid);
  pid_ = pid;
  // Readable when the child exits, so that wait_for_exit() wakes at once (-1 where the kernel
  // has no pidfd_open: wait_for_exit() then polls).
  // A raw syscall: glibc 2.36's <sys/pidfd.h> declares pidfd_open without extern "C".
  exit_fd_ = static_cast<int>(::syscall(SYS_pidfd_open, pid, 0));

  // The report pipe closes on a successful exec; a StartFailure arrives otherwise.
  StartFailure failure{};
  ssize_t got;
  do got = ::read(report[0], &failure, sizeof failure);
  while (got < 0 && errno == EINTR);
  ::close(report[0]);
  if (got == static_cast<ssize_t>(sizeof failure)) {
    stop(0.0);
    if (exit_fd_ >= 0) ::close(exit_fd_);  // no destructor runs after a throwing constructor
    throw std::runtime_error(start_failure_text(failure, executable, working_directory));
  }
}

ChildProcess::~ChildProcess() {
  stop(1.0);
  if (exit_fd_ >= 0) ::close(exit_fd_);
}

void ChildProcess::on_reaped(int status) {
  reaped_ = true;
  status_known_ = true;
  status_ = status;
  unregister_child(pid_);
  // Whatever the child started in its group (mpirun's ranks, a script's children) goes too.
  ::kill(-pid_, SIGKILL);
}

bool ChildProcess::running() {
  if (reaped_ || pid_ <= 0) return false;
  for (;;) {
    int status = 0;
    const pid_t result = ::waitpid(pid_, &status, WNOHANG);
    if (result == 0) return true;
    if (result == pid_) {
      on_reaped(status);
      return false;
    }
    if (errno == EINTR) continue;
    // ECHILD: reaped elsewhere (SIGCHLD ignored, or a waitpid(-1) in other code); it is gone.
    reaped_ = true;
    unregister_child(pid_);
    return false;
  }
}

bool ChildProcess::wait_for_exit(double timeout_seconds) {
  const auto end = std::chrono::steady_clock::now() +
                   std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                       std::chrono::duration<double>(std::max(timeout_seconds, 0.0)));
  auto pause = std::chrono::milliseconds(1);
  while (running()) {
    const auto now = std::chrono::steady_clock::now();
    if (now >= end) return false;
    if (exit_fd_ >= 0) {
      // Block until the exit itself: a short-lived solver run (ccx, once per coupling
      // iteration) must not lose a polling interval every time.
      const auto left = std::chrono::ceil<std::chrono::milliseconds>(end - now).count();
      pollfd exit_event{exit_fd_, POLLIN, 0};
      if (::poll(&exit_event, 1, static_cast<int>(std::min<long long>(left, INT_MAX))) >= 0 ||
          errno == EINTR)
        continue;
      ::close(exit_fd_);  // poll() refuses the descriptor: fall back to polling waitpid
      exit_fd_ = -1;
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::milliseconds(20));
  }
  return true;
}

void ChildProcess::stop(double grace_seconds) {
  if (!running()) return;
  // To the group first; to the process itself if it left the group (or never joined it).
  const auto signal_all = [this](int signal) {
    if (::kill(-pid_, signal) != 0) ::kill(pid_, signal);
  };
  signal_all(SIGTERM);
  if (wait_for_exit(grace_seconds)) return;
  signal_all(SIGKILL);
  int status = 0;
  pid_t result;
  do result = ::waitpid(pid_, &status, 0);
  while (result < 0 && errno == EINTR);
  if (result == pid_) {
    on_reaped(status);
  } else {
    reaped_ = true;
    unregister_child(pid_);
  }
}

std::string ChildProcess::describe_exit() const {
  if (!reaped_) return "is running";
  if (!status_known_) return "exited (exit status unknown)";
  if (WIFEXITED(status_)) return "exited with code " + std::to_string(WEXITSTATUS(status_));
  if (WIFSIGNALED(status_)) {
    const int signal = WTERMSIG(status_);
    const char* name = ::strsignal(signal);
    return "killed by signal " + std::to_string(signal) +
           (name != nullptr ? " (" + std::string(name) + ")" : std::string()) +
           (WCOREDUMP(status_) ? ", core dumped" : "");
  }
  return "stopped";
}

int ChildProcess::exit_code() const {
  return reaped_ && status_known_ && WIFEXITED(status_) ? WEXITSTATUS(status_) : -1;
}

std::filesystem::path find_executable(const std::string& command,
                                      const std::filesystem::path& working_directory) {
  namespace fs = std::filesystem;
  if (command.empty()) throw std::runtime_error("empty command");
  if (command.find('/') != std::string::npos) {
    const fs::path candidate = fs::absolute(working_directory / command).lexically_normal();
    if (const auto why = path_problem(candidate, PathKind::kAny); !why.empty())
      throw std::runtime_error("executable " + candidate.string() + " " + why);
    if (!is_executable_file(candidate))
      throw std::runtime_error(candidate.string() + " is not an executable file");
    return candidate;
  }
  const fs::path local = fs::absolute(working_directory / command);
  if (is_executable_file(local)) return local;
  const char* search_path = std::getenv("PATH");
  std::string directories = search_path != nullptr ? search_path : "";
  std::size_t start = 0;
  while (start <= directories.size()) {
    const std::size_t end = std::min(directories.find(':', start), directories.size());
    const std::string directory = directories.substr(start, end - start);
    const fs::path candidate = fs::path(directory.empty() ? "." : directory) / command;
    if (is_executable_file(candidate)) return fs::absolute(candidate);
    start = end + 1;
  }
  std::string message =
      "executable '" + command + "' not found in " + working_directory.string() + " or on PATH";
  if (path_problem(local, PathKind::kAny).empty())
    message += " (" + local.string() + " exists but is not executable)";
  throw std::runtime_error(message);
}

void kill_all_children() noexcept {
  for (auto& slot : g_live_children) {
    const pid_t pid = slot.load();
    if (pid > 0) ::kill(-pid, SIGKILL);
  }
}

CommandOutput run_to_end(const ChildOptions& options, double timeout_seconds) {
  constexpr double kStopGraceSeconds = 1.0;
  CommandOutput result;
  {
    ChildProcess child(options);
    result.finished = child.wait_for_exit(timeout_seconds);
    if (!result.finished) child.stop(kStopGraceSeconds);
    result.exit_code = child.exit_code();
    result.exit_description = child.describe_exit();
  }
  std::ifstream in(options.log_file, std::ios::binary);
  result.output.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  in.close();
  std::error_code ignored;
  std::filesystem::remove(options.log_file, ignored);
  return result;
}

std::string read_last_lines(const std::filesystem::path& file, std::size_t count) {
  // The tail of a long log is all we need: read at most its last 64 KiB.
  constexpr std::streamoff kTailBytes = 1 << 16;
  std::ifstream in(file, std::ios::binary);
  if (!in || count == 0) return "";
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(std::max<std::streamoff>(0, size - kTailBytes));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  std::size_t begin = text.size();  // the newline before the earliest line found so far
  for (std::size_t lines = 0; lines < count; ++lines) {
    const std::size_t newline = begin == 0 ? std::string::npos : text.rfind('\n', begin - 1);
    if (newline == std::string::npos) return text;  // fewer lines than asked for
    begin = newline;
  }
  return text.substr(begin + 1);
}

}  // namespace cocopp

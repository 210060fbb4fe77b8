#include "coupler/app/case_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace cocopp {

namespace {

/// The pid the lock's holder wrote into the file ("" if none can be read).
std::string holder_of(int fd) {
  char text[32] = {};
  const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
  if (n <= 0) return "";
  std::string pid(text, static_cast<std::size_t>(n));
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
  return pid;
}

int locked_file(const std::filesystem::path& file) {
  // O_NOFOLLOW: a symlink planted at the lock's name must not lock (or truncate) its target.
  const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0)
    throw std::runtime_error("cannot create the lock file " + file.string() +
                             " (the run writes next to it): " + std::strerror(errno));
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int reason = errno;
    const std::string holder = holder_of(fd);
    ::close(fd);
    if (reason == EWOULDBLOCK)
      throw std::runtime_error("another cocopp run" +
                               (holder.empty() ? std::string() : " (pid " + holder + ")") +
                               " is running this case: it holds " + file.string() +
                               ". Wait for it to end, or stop it, before running the case again");
    throw std::runtime_error("cannot lock " + file.string() + ": " + std::strerror(reason));
  }
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, pid.data(), pid.size(), 0) < 0) {
    const int reason = errno;
    ::close(fd);
    throw std::runtime_error("cannot write the lock file " + file.string() + ": " +
                             std::strerror(reason));
  }
  return fd;
}

int lock_file(const std::filesystem::path& file) {
  std::error_code error;
  std::filesystem::create_directories(file.parent_path(), error);
  if (error)
    throw std::runtime_error("cannot use the directory " + file.parent_path().string() + ": " +
                             error.message());
  // A run removes its lock files when it ends (release): a lock taken on a file that was
  // removed (or replaced) between our open and our flock locks nothing; then again.
  for (int attempt = 0;; ++attempt) {
    const int fd = locked_file(file);
    struct stat held {};
    struct stat named {};
    if (::fstat(fd, &held) == 0 && ::lstat(file.c_str(), &named) == 0 &&
        held.st_dev == named.st_dev && held.st_ino == named.st_ino)
      return fd;
    ::close(fd);
    if (attempt == 10)
      throw std::runtime_error("cannot lock " + file.string() +
                               ": it is removed and created again as it is locked");
  }
}

}  // namespace

CaseLock::CaseLock(const std::vector<std::filesystem::path>& files) {
  try {
    for (const auto& file : files) held_.emplace_back(file, lock_file(file));
  } catch (...) {
    release();
    throw;
  }
}

CaseLock::~CaseLock() {
  release();
}

void CaseLock::release() noexcept {
  // Removed while still locked, so that no run can take a lock on it that another would not
  // see (lock_file checks that the file it locked is still the one the name gives). A run that
  // dies leaves its file, unlocked, for the next.
  for (const auto& [file, fd] : held_) {
    ::unlink(file.c_str());
    ::close(fd);
  }
  held_.clear();
}

}  // namespace cocopp

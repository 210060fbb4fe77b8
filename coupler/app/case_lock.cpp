#include "coupler/app/case_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
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

int lock_file(const std::filesystem::path& file) {
  std::error_code error;
  std::filesystem::create_directories(file.parent_path(), error);
  if (error)
    throw std::runtime_error("cannot use the directory " + file.parent_path().string() + ": " +
                             error.message());
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

}  // namespace

CaseLock::CaseLock(const std::vector<std::filesystem::path>& files) {
  try {
    for (const auto& file : files) descriptors_.push_back(lock_file(file));
  } catch (...) {
    release();
    throw;
  }
}

CaseLock::~CaseLock() {
  release();
}

void CaseLock::release() noexcept {
  for (int fd : descriptors_) ::close(fd);  // closing drops the lock; the file stays
  descriptors_.clear();
}

}  // namespace cocopp

#pragma once
// CaseLock: one run of a case at a time. Two runs of one case would write the same results
// file and talk through the same solver channels; the second must stop before it touches any
// of them, and say which process holds the case. An exclusive flock on a lock file in the
// results directory (<name>.lock) and in each solver working directory (.cocopp.lock), held
// for the run's life; the kernel drops it when the process ends, however it ends. The files
// are removed when the run ends (a killed run leaves them, unlocked).
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace cocopp {

class CaseLock {
 public:
  /// Locks `files` in order (creating their directories). Throws std::runtime_error naming
  /// the file and, where another run holds it, that run's pid; or naming the directory that
  /// cannot be used (not writable, a file in the way, a name too long, ...).
  explicit CaseLock(const std::vector<std::filesystem::path>& files);
  ~CaseLock();
  CaseLock(const CaseLock&) = delete;
  CaseLock& operator=(const CaseLock&) = delete;

 private:
  void release() noexcept;
  std::vector<std::pair<std::filesystem::path, int>> held_;  ///< each file and its descriptor
};

}  // namespace cocopp

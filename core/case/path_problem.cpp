#include "core/case/path_problem.hpp"

#include <unistd.h>

#include <system_error>

namespace cocopp {

namespace {

std::string reason(const std::error_code& error) {
  if (error == std::errc::too_many_symbolic_link_levels)
    return "is a loop of symbolic links (or more than 40 links deep)";
  if (error == std::errc::filename_too_long)
    return "has a name longer than the file system allows (255 bytes a name, 4096 a path)";
  if (error == std::errc::not_a_directory) return "does not exist (a part of it is a file)";
  if (error == std::errc::permission_denied) return "cannot be reached (permission denied)";
  if (error == std::errc::no_such_file_or_directory) return "does not exist";
  return "cannot be used (" + error.message() + ")";
}

}  // namespace

std::string path_problem(const std::filesystem::path& path, PathKind kind) {
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (error) return reason(error);
  if (!std::filesystem::exists(status)) return "does not exist";
  if (kind == PathKind::kDirectory && !std::filesystem::is_directory(status))
    return "is not a directory";
  if (kind == PathKind::kRegularFile && !std::filesystem::is_regular_file(status))
    return std::filesystem::is_directory(status) ? "is a directory, not a file"
                                                 : "is not a regular file";
  return "";
}

std::string creation_problem(const std::filesystem::path& directory) {
  const std::string why = path_problem(directory, PathKind::kDirectory);
  if (why != "does not exist") return why;
  std::filesystem::path existing = std::filesystem::absolute(directory).parent_path();
  while (path_problem(existing, PathKind::kAny) == "does not exist" && existing.has_parent_path() &&
         existing != existing.parent_path())
    existing = existing.parent_path();
  if (const auto problem = path_problem(existing, PathKind::kDirectory); !problem.empty())
    return "cannot be created: " + existing.string() + " " + problem;
  if (::access(existing.c_str(), W_OK | X_OK) != 0)
    return "cannot be created: " + existing.string() + " is not writable";
  return "";
}

std::string describe_filesystem_error(const std::filesystem::filesystem_error& error) {
  const std::string path = error.path1().empty() ? "a path" : error.path1().string();
  return path + " " + reason(error.code());
}

}  // namespace cocopp

#pragma once
// Why a path from a case file cannot be used, in words a user can act on. The std::filesystem
// calls that throw say "filesystem error: status: Too many levels of symbolic links [...]";
// these never throw and name the problem (a loop of links, a name too long, a file where a
// directory belongs) so that the caller can put it next to the case file's line and key.
#include <filesystem>
#include <string>

namespace cocopp {

enum class PathKind { kDirectory, kRegularFile, kAny };

/// "" if `path` exists and is of `kind`; else "does not exist", "is a loop of symbolic
/// links", "has a name longer than the file system allows", "is not a directory", ...
std::string path_problem(const std::filesystem::path& path, PathKind kind);

/// "" if `directory` exists as a directory, or its nearest existing folder is one that can be
/// written to (the run creates the rest); else why it cannot be created: "cannot be created:
/// /a/b is not a directory", "... /a is not writable".
std::string creation_problem(const std::filesystem::path& directory);

/// The reason of a std::filesystem error in the same words, with the path it concerns:
/// "/a/b is a loop of symbolic links".
std::string describe_filesystem_error(const std::filesystem::filesystem_error& error);

}  // namespace cocopp

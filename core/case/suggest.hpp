#pragma once
// Helpers for error messages: nearest-name suggestions and lists.
#include <string>
#include <vector>

namespace cocopp {

/// Levenshtein edit distance between two strings.
std::size_t edit_distance(const std::string& a, const std::string& b);

/// The candidate closest to `word`, if it is within a sensible distance (fewer than half the
/// letters differ, at least 2 edits allowed), else "".
std::string nearest(const std::string& word, const std::vector<std::string>& candidates);

/// "; did you mean 'x'?" for the closest candidate within a sensible distance, else "".
std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates);

/// "a, b, c"
std::string join(const std::vector<std::string>& words, const std::string& separator = ", ");

}  // namespace cocopp

#pragma once
// The slips a hand-written case file most often has, named in words at their line: bytes that
// are not text or not UTF-8, JSON that is not JSON (a trailing or a missing comma, a comment),
// and the YAML indentation slips yaml-cpp reports as "end of map not found" or "illegal map
// value".

#include <optional>
#include <string>

namespace cocopp {

/// A case file is UTF-8 text: throws CaseError "file:line:col: ..." at a NUL or another
/// control character but tab, line feed and carriage return (a binary or damaged file; yaml-cpp's
/// LoadAll loops for ever after a NUL), and at the first byte sequence that is not UTF-8.
void check_text(const std::string& text, const std::string& file_name);

/// A file named *.json must be JSON (yaml-cpp would take YAML's extensions of it: a trailing
/// comma, a comment): throws CaseError at the first thing JSON does not allow, in words.
void check_json(const std::string& text, const std::string& file_name);

/// A YAML text's first indentation slip at or before line `line` (0-based): a tab in the
/// indentation, a line indented more than the key above it that already has a value, or a
/// line indented to no enclosing mapping's column. "line:col: what is wrong", or nothing when
/// the indentation is consistent there (the error is of another kind).
std::optional<std::string> indentation_slip(const std::string& text, int line);

}  // namespace cocopp

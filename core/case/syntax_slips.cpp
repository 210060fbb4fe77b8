#include "core/case/syntax_slips.hpp"

#include <cctype>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/case/settings.hpp"

namespace cocopp {

namespace {

std::string at(int line, int column) {
  return std::to_string(line) + ":" + std::to_string(column);
}

/// 1-based line and column of byte `index` of `text`.
std::string position_of(const std::string& text, std::size_t index) {
  int line = 1;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < index && i < text.size(); ++i)
    if (text[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
  return at(line, static_cast<int>(index - line_start) + 1);
}

/// Bytes of the UTF-8 sequence at `i`, or 0 if it is not one (overlong forms and surrogates
/// included).
std::size_t utf8_length(const std::string& text, std::size_t i) {
  const auto lead = static_cast<unsigned char>(text[i]);
  if (lead < 0x80) return 1;
  std::size_t length = 0;
  unsigned smallest = 0;
  if ((lead & 0xe0) == 0xc0) {
    length = 2;
    smallest = 0x80;
  } else if ((lead & 0xf0) == 0xe0) {
    length = 3;
    smallest = 0x800;
  } else if ((lead & 0xf8) == 0xf0) {
    length = 4;
    smallest = 0x10000;
  } else {
    return 0;
  }
  if (i + length > text.size()) return 0;
  unsigned code = lead & (0x7fu >> length);
  for (std::size_t k = 1; k < length; ++k) {
    const auto next = static_cast<unsigned char>(text[i + k]);
    if ((next & 0xc0) != 0x80) return 0;
    code = (code << 6) | (next & 0x3fu);
  }
  if (code < smallest || code > 0x10ffff || (code >= 0xd800 && code <= 0xdfff)) return 0;
  return length;
}

bool ends_with(const std::string& text, const std::string& end) {
  return text.size() >= end.size() && text.compare(text.size() - end.size(), end.size(), end) == 0;
}

/// Where nlohmann's parser stopped: the bytes it read (the last of them ends the token it could
/// not take) and why.
struct JsonError : nlohmann::json_sax<nlohmann::json> {
  std::size_t position = 0;
  std::string message;
  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override { return true; }
  bool key(string_t&) override { return true; }
  bool end_object() override { return true; }
  bool start_array(std::size_t) override { return true; }
  bool end_array() override { return true; }
  bool parse_error(std::size_t where, const std::string& /*last_token*/,
                   const nlohmann::detail::exception& error) override {
    position = where;
    message = error.what();
    return false;
  }
};

/// nlohmann's message without its "[json.exception...] parse error at line 3, column 5: ".
std::string plain(const std::string& message) {
  const auto colon = message.find(": ");
  return colon == std::string::npos ? message : message.substr(colon + 2);
}

/// The last non-blank byte before `end`, or npos.
std::size_t last_non_blank(const std::string& text, std::size_t end) {
  while (end > 0) {
    const char c = text[--end];
    if (c != ' ' && c != '\t' && c != '\n' && c != '\r') return end;
  }
  return std::string::npos;
}

bool ends_a_value(char c) {
  return c == '"' || c == '}' || c == ']' || (c >= '0' && c <= '9') || c == 'e' || c == 'l' ||
         c == '.';
}

bool starts_a_value(char c) {
  return c == '"' || c == '{' || c == '[' || c == '-' || (c >= '0' && c <= '9') || c == 't' ||
         c == 'f' || c == 'n';
}

/// Where the token ending at byte `last` starts: a string's opening quote, a number's or a
/// literal's first character, else `last` itself (a bracket, a comma, a colon).
std::size_t token_start(const std::string& text, std::size_t last) {
  const auto part_of_word = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '+';
  };
  if (text[last] == '"' && last > 0) {
    std::size_t start = last - 1;
    while (start > 0 && !(text[start] == '"' && text[start - 1] != '\\')) --start;
    return start;
  }
  std::size_t start = last;
  while (start > 0 && part_of_word(text[last]) && part_of_word(text[start - 1])) --start;
  return start;
}

/// The words for a JSON syntax error at the token that ends at byte `last`.
std::string json_slip(const std::string& text, std::size_t last, const std::string& message) {
  const std::size_t start = token_start(text, last);
  const std::string where = position_of(text, start);
  const char first = text[start];
  const std::size_t before = last_non_blank(text, start);
  const char previous = before == std::string::npos ? '\0' : text[before];
  if ((first == '}' || first == ']') && previous == ',')
    return position_of(text, before) + ": a comma before the closing '" + first + "' at " + where +
           ": JSON allows no trailing comma; remove it";
  if (first == '/' || first == '#')
    return where +
           ": a comment: JSON has none; remove it (or write the case in YAML, which "
           "has # comments)";
  if (message.find("expected end of input") != std::string::npos)
    return where +
           ": content after the end of the case (text after the JSON object): a case file "
           "holds one; remove it";
  if (starts_a_value(first) && ends_a_value(previous) &&
      message.find("expected") != std::string::npos)
    return position_of(text, before + 1) + ": a comma is missing after " +
           position_of(text, before) + " (before " + text.substr(start, last + 1 - start) + " at " +
           where + ")";
  if (first == '\'') return where + ": a string in single quotes: JSON quotes strings with \"";
  return where + ": not JSON: " + plain(message);
}

/// One line of a YAML text as the indentation check sees it.
struct YamlLine {
  int number = 0;      ///< 1-based
  int indent = 0;      ///< spaces before its content
  std::string text;    ///< its content, comment stripped
  bool opens = false;  ///< a key without a value or a bare "-": the next line may go deeper
};

/// The content of a line without its comment (a '#' after a blank, outside quotes).
std::string without_comment(const std::string& content) {
  char quote = '\0';
  for (std::size_t i = 0; i < content.size(); ++i) {
    const char c = content[i];
    if (quote) {
      if (c == quote) quote = '\0';
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '#' && (i == 0 || content[i - 1] == ' ')) {
      std::size_t end = i;
      while (end > 0 && content[end - 1] == ' ') --end;
      return content.substr(0, end);
    }
  }
  return content;
}

/// Opening minus closing brackets outside quotes: 0 where a flow value ends on its line.
int bracket_balance(const std::string& content) {
  int balance = 0;
  char quote = '\0';
  for (const char c : content) {
    if (quote) {
      if (c == quote) quote = '\0';
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '{' || c == '[') {
      ++balance;
    } else if (c == '}' || c == ']') {
      --balance;
    }
  }
  return balance;
}

/// Whether a line's content leaves its value to the lines below: "key:", "-", "key: |".
bool opens_a_block(const std::string& text) {
  if (text == "-" || ends_with(text, ":")) return true;
  for (const char* indicator : {": |", ": >", ": |-", ": >-", ": |+", ": >+"})
    if (ends_with(text, indicator)) return true;
  return false;
}

bool is_block_scalar(const std::string& text) {
  return opens_a_block(text) && (text.back() != ':' && text != "-");
}

/// Column of the content after a list item's dash ("- key: v" at 2 gives 4), or -1.
int item_content_indent(const YamlLine& line) {
  if (line.text.size() < 2 || line.text[0] != '-' || line.text[1] != ' ') return -1;
  std::size_t k = 1;
  while (k < line.text.size() && line.text[k] == ' ') ++k;
  return line.indent + static_cast<int>(k);
}

std::string spaces(int count) {
  return std::to_string(count) + (count == 1 ? " space" : " spaces");
}

std::string shown(const std::string& text) {
  return "'" + (text.size() > 40 ? text.substr(0, 37) + "..." : text) + "'";
}

}  // namespace

void check_text(const std::string& text, const std::string& file_name) {
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    const bool control = (c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f;
    const std::size_t length = control ? 0 : utf8_length(text, i);
    if (length == 0) {
      char byte[8];
      std::snprintf(byte, sizeof byte, "0x%02x", c);
      throw CaseError(file_name + ":" + position_of(text, i) +
                      (control ? std::string(": a control character (byte ") + byte +
                                     "): a case file is text (YAML or JSON); is this the right "
                                     "file?"
                               : std::string(": a byte that is not UTF-8 (") + byte +
                                     "): a case file is UTF-8 text; was it saved in another "
                                     "encoding (Latin-1, Windows-1252)?"));
    }
    i += length;
  }
}

void check_json(const std::string& text, const std::string& file_name) {
  if (!ends_with(file_name, ".json")) return;
  JsonError error;
  if (nlohmann::json::sax_parse(text, &error)) return;
  // The parser has read `position` bytes, the failing token last.
  const std::size_t read = std::min(error.position, text.size());
  throw CaseError(file_name + ":" + json_slip(text, read > 0 ? read - 1 : 0, error.message));
}

std::optional<std::string> indentation_slip(const std::string& text, int line) {
  std::vector<int> levels;  // the columns of the open mappings and lists, outermost first
  YamlLine previous;
  YamlLine first;
  int block_scalar_parent = -1;  // inside a block scalar (|, >) below a line at this indent
  std::size_t begin = 0;
  for (int number = 1; begin <= text.size() && number <= line + 1; ++number) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    std::string raw = text.substr(begin, end - begin);
    begin = end + 1;
    if (!raw.empty() && raw.back() == '\r') raw.pop_back();
    std::size_t k = 0;
    while (k < raw.size() && (raw[k] == ' ' || raw[k] == '\t')) {
      if (raw[k] == '\t' && block_scalar_parent < 0)
        return at(number, static_cast<int>(k) + 1) +
               ": a tab character in the indentation of line " + std::to_string(number) +
               ": YAML indents with spaces only; replace the tab by spaces";
      ++k;
    }
    const std::string content = without_comment(raw.substr(k));
    const int indent = static_cast<int>(k);
    if (content.empty()) continue;
    if (block_scalar_parent >= 0) {
      if (indent > block_scalar_parent) continue;
      block_scalar_parent = -1;
    }
    if (indent == 0 && (content.rfind("---", 0) == 0 || content.rfind("...", 0) == 0)) continue;
    // Flow style over several lines ({... or [... left open) is not judged by its indentation.
    if (bracket_balance(content) != 0) return std::nullopt;
    const YamlLine current{number, indent, content, opens_a_block(content)};
    if (levels.empty()) {
      levels.push_back(indent);
      first = current;
    } else if (indent > levels.back()) {
      if (!previous.opens)
        return at(number, indent + 1) + ": line " + std::to_string(number) + " is indented more (" +
               spaces(indent) + ") than line " + std::to_string(previous.number) + " above it (" +
               spaces(previous.indent) + "), whose key already has its value (" +
               shown(previous.text) +
               "): the keys of one mapping line up; indent the two lines alike";
      levels.push_back(indent);
    } else if (indent < levels.back()) {
      const std::vector<int> open = levels;
      while (!levels.empty() && levels.back() > indent) levels.pop_back();
      if (levels.empty())
        return at(number, indent + 1) + ": line " + std::to_string(number) +
               " starts further left (column " + std::to_string(indent + 1) +
               ") than the file's first key (line " + std::to_string(first.number) + ", column " +
               std::to_string(first.indent + 1) +
               "), so YAML ends the case before it: indent the top-level keys alike";
      if (levels.back() != indent) {
        std::string columns;
        for (const int level : open)
          columns += (columns.empty() ? "" : ", ") + std::to_string(level + 1);
        return at(number, indent + 1) + ": line " + std::to_string(number) + " is indented by " +
               spaces(indent) +
               ", which lines it up with none of the mappings above it (their keys start in "
               "columns " +
               columns + "): indent it as the keys of its mapping";
      }
    }
    if (const int item = item_content_indent(current); item >= 0) levels.push_back(item);
    if (is_block_scalar(content)) block_scalar_parent = indent;
    previous = current;
  }
  return std::nullopt;
}

}  // namespace cocopp

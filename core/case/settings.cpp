#include "core/case/settings.hpp"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/parser.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <unordered_map>

#include "core/case/suggest.hpp"
#include "core/case/syntax_slips.hpp"

namespace cocopp {

namespace {

template <class T>
const char* type_name() {
  if constexpr (std::is_same_v<T, double>) return "a number";
  if constexpr (std::is_same_v<T, int>) return "an integer";
  if constexpr (std::is_same_v<T, bool>) return "true or false";
  if constexpr (std::is_same_v<T, std::string>) return "a string";
  if constexpr (std::is_same_v<T, std::vector<double>>) return "a list of numbers";
  if constexpr (std::is_same_v<T, std::vector<std::string>>) return "a list of strings";
  return "a value";
}

std::string location(const std::filesystem::path& file, const YAML::Mark& mark) {
  std::string out = file.string();
  if (!mark.is_null())
    out += ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
  return out;
}

/// What the YAML parser accepts but a case file must not have, each an error at its line:
/// a key given twice (the parser keeps both and a lookup finds the first, so the second would
/// be ignored silently) and a key that is not a plain name (a list or a mapping as a key).
void check_keys(const YAML::Node& node, const std::filesystem::path& file,
                const std::string& path) {
  if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i)
      check_keys(node[i], file, path + "[" + std::to_string(i) + "]");
    return;
  }
  if (!node.IsMap()) return;
  std::map<std::string, YAML::Mark> seen;
  for (auto it = node.begin(); it != node.end(); ++it) {
    // A copy: yaml-cpp's iterator hands out a temporary pair, whose members die with it.
    const YAML::Node key = it->first;
    const std::string where = path.empty() ? "" : " in '" + path + "'";
    if (key.IsNull())
      throw CaseError(location(file, key.Mark()) + ": a key" + where +
                      " is empty or null (~, null or nothing before the colon): keys are "
                      "plain names");
    if (!key.IsScalar())
      throw CaseError(location(file, key.Mark()) + ": a key" + where +
                      " is a list or a mapping: keys are plain names");
    const auto [first, inserted] = seen.emplace(key.Scalar(), key.Mark());
    if (!inserted)
      throw CaseError(location(file, key.Mark()) + ": key '" + key.Scalar() + "'" + where +
                      " is given twice (first at line " + std::to_string(first->second.line + 1) +
                      "): only one of them would count; remove the other");
    check_keys(it->second, file, path.empty() ? key.Scalar() : path + "." + key.Scalar());
  }
}

/// Where a second document starts in `text`, if it has one. A parser that builds nothing reads
/// at most two documents (YAML::LoadAll would read them all, however many there are).
std::optional<YAML::Mark> second_document_start(const std::string& text) {
  struct DocumentStarts : YAML::EventHandler {
    std::vector<YAML::Mark> starts;
    void OnDocumentStart(const YAML::Mark& mark) override { starts.push_back(mark); }
    void OnDocumentEnd() override {}
    void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
    void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
    void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  const std::string&) override {}
    void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                         YAML::EmitterStyle::value) override {}
    void OnSequenceEnd() override {}
    void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                    YAML::EmitterStyle::value) override {}
    void OnMapEnd() override {}
  } handler;
  std::istringstream in(text);
  YAML::Parser parser(in);
  for (int i = 0; i < 2 && parser.HandleNextDocument(handler); ++i) {
  }
  if (handler.starts.size() < 2) return std::nullopt;
  return handler.starts[1];
}

}  // namespace

/// Shared by all Settings of one file: which keys each mapping's readers asked for.
struct Settings::Document {
  std::filesystem::path file;
  struct Mapping {
    YAML::Node node;
    std::string path;
    std::set<std::string> known_keys;
  };
  std::vector<Mapping> mappings;
  /// Entries of `mappings` by key path, so that finding a mapping's entry does not scan them
  /// all (a list of n mappings would take n^2). A path names one node, except the empty
  /// mappings child_or_empty makes for an absent key: those are told apart by identity.
  std::unordered_map<std::string, std::vector<std::size_t>> by_path;
};

Settings Settings::load_file(const std::filesystem::path& file) {
  // A case file is a few kilobytes; a device, a pipe or a huge file would be read whole first.
  std::error_code error;
  const auto status = std::filesystem::status(file, error);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw CaseError(file.string() + ": not a regular file (" +
                    (std::filesystem::is_directory(status) ? "a directory" : "a device or a pipe") +
                    "): give the path of the case's YAML or JSON file");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw CaseError(file.string() + ": cannot open the file");
  std::string text(kMaxCaseFileBytes + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (text.size() > kMaxCaseFileBytes)
    throw CaseError(file.string() + ": larger than the " + std::to_string(kMaxCaseFileBytes >> 20) +
                    " MiB a case file may have: is it the case file? (solver inputs and meshes "
                    "belong in the solvers' working directories)");
  return load_string(text, file.string());
}

Settings Settings::load_string(const std::string& text, const std::string& file_name) {
  auto document = std::make_shared<Document>();
  document->file = file_name;
  check_text(text, file_name);
  check_json(text, file_name);
  YAML::Node root;
  std::optional<YAML::Mark> second_document;
  try {
    root = YAML::Load(text);
    second_document = second_document_start(text);
  } catch (const YAML::DeepRecursion& e) {
    // yaml-cpp stops at 500 levels with the words "bad file"; say what is wrong instead.
    throw CaseError(location(file_name, e.mark) +
                    ": lists and mappings nested more than 500 deep: a case file needs a few "
                    "levels; look for brackets or indentation that never close");
  } catch (const YAML::Exception& e) {
    // yaml-cpp names most indentation slips "end of map not found" or "illegal map value":
    // say which line is out of line instead, where the indentation tells.
    if (const auto slip = indentation_slip(text, e.mark.line))
      throw CaseError(file_name + ":" + *slip);
    throw CaseError(location(file_name, e.mark) + ": syntax error: " + e.msg);
  }
  if (!root.IsMap())
    throw CaseError(location(file_name, root.Mark()) +
                    ": the file must hold a mapping of keys (YAML) or an object (JSON)");
  // Content after the first document (a second YAML document, text after the JSON object)
  // would be ignored silently.
  if (second_document) {
    if (const auto slip = indentation_slip(text, second_document->line))
      throw CaseError(file_name + ":" + *slip);
    throw CaseError(location(file_name, *second_document) +
                    ": content after the end of the case (a second YAML document, or text "
                    "after the JSON object): a case file holds one; remove it");
  }
  check_keys(root, file_name, "");
  return Settings(document, root, "");
}

Settings::Settings(std::shared_ptr<Document> document, YAML::Node node, std::string path)
    : document_(std::move(document)), node_(std::move(node)), path_(std::move(path)) {
  // One registry entry per distinct mapping, so copies of a Settings share known keys.
  auto& entries = document_->by_path[path_];
  for (const std::size_t i : entries)
    if (document_->mappings[i].node.is(node_)) {
      index_ = i;
      return;
    }
  index_ = document_->mappings.size();
  entries.push_back(index_);
  document_->mappings.push_back({node_, path_, {}});
}

const std::filesystem::path& Settings::file() const {
  return document_->file;
}

std::filesystem::path Settings::base_directory() const {
  auto dir = document_->file.parent_path();
  return dir.empty() ? std::filesystem::path(".") : dir;
}

std::string Settings::key_path(const std::string& key) const {
  return path_.empty() ? key : (key.empty() ? path_ : path_ + "." + key);
}

std::string Settings::where(const std::string& key) const {
  if (!key.empty()) {
    const YAML::Node value = node_[key];
    if (value.IsDefined()) return location(document_->file, value.Mark());
  }
  return location(document_->file, node_.Mark());
}

void Settings::fail(const std::string& key, const std::string& message) const {
  const std::string name = key_path(key);
  throw CaseError(where(key) + ": " + (name.empty() ? "" : "'" + name + "': ") + message);
}

void Settings::allow(const std::string& key) const {
  document_->mappings[index_].known_keys.insert(key);
}

YAML::Node Settings::lookup(const std::string& key) const {
  allow(key);
  const YAML::Node& const_node = node_;  // const access never inserts a key
  return const_node[key];
}

bool Settings::has(const std::string& key) const {
  YAML::Node value = lookup(key);
  return value.IsDefined() && !value.IsNull();
}

template <class T>
T Settings::convert(const YAML::Node& value, const std::string& key) const {
  try {
    if constexpr (std::is_same_v<T, std::vector<double>> ||
                  std::is_same_v<T, std::vector<std::string>>) {
      if (!value.IsSequence()) throw YAML::BadConversion(value.Mark());
    } else if (!value.IsScalar()) {
      throw YAML::BadConversion(value.Mark());
    }
    T result = value.as<T>();
    if constexpr (std::is_same_v<T, double>)
      if (!std::isfinite(result))
        fail(key, "must be a finite number, got '" + value.Scalar() + "'");
    return result;
  } catch (const YAML::Exception&) {
    std::string got = value.IsScalar() ? "'" + value.Scalar() + "'"
                                       : (value.IsSequence() ? "a list" : "a mapping");
    fail(key, std::string("expected ") + type_name<T>() + ", got " + got);
  }
}

std::string Settings::misspelling_hint(const std::string& key) const {
  if (!node_.IsMap()) return "";
  const auto& known = document_->mappings[index_].known_keys;
  std::vector<std::string> unread;
  std::map<std::string, YAML::Mark> marks;
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    const YAML::Node name = it->first;
    if (!name.IsScalar() || known.count(name.Scalar()) != 0 || name.Scalar() == key) continue;
    unread.push_back(name.Scalar());
    marks.emplace(name.Scalar(), name.Mark());
  }
  const std::string near = nearest(key, unread);
  if (near.empty()) return "";
  return "; is '" + near + "' (line " + std::to_string(marks.at(near).line + 1) +
         ") a misspelling of it?";
}

template <class T>
T Settings::required(const std::string& key) const {
  YAML::Node value = lookup(key);
  if (!value.IsDefined() || value.IsNull())
    fail("", "missing required key '" + key_path(key) + "'" + misspelling_hint(key));
  return convert<T>(value, key);
}

template <class T>
T Settings::get(const std::string& key, const T& default_value) const {
  YAML::Node value = lookup(key);
  if (!value.IsDefined() || value.IsNull()) return default_value;
  return convert<T>(value, key);
}

template double Settings::required<double>(const std::string&) const;
template int Settings::required<int>(const std::string&) const;
template bool Settings::required<bool>(const std::string&) const;
template std::string Settings::required<std::string>(const std::string&) const;
template std::vector<double> Settings::required<std::vector<double>>(const std::string&) const;
template std::vector<std::string> Settings::required<std::vector<std::string>>(
    const std::string&) const;
template double Settings::get<double>(const std::string&, const double&) const;
template int Settings::get<int>(const std::string&, const int&) const;
template bool Settings::get<bool>(const std::string&, const bool&) const;
template std::string Settings::get<std::string>(const std::string&, const std::string&) const;
template std::vector<double> Settings::get<std::vector<double>>(const std::string&,
                                                                const std::vector<double>&) const;
template std::vector<std::string> Settings::get<std::vector<std::string>>(
    const std::string&, const std::vector<std::string>&) const;

namespace {
std::string format_number(double value) {
  std::ostringstream out;
  out.precision(12);
  out << value;
  return out.str();
}
}  // namespace

bool Range::contains(double value) const {
  const bool above = min_exclusive ? value > min : value >= min;
  const bool below = max_exclusive ? value < max : value <= max;
  return above && below;
}

std::string Range::describe() const {
  const bool bounded_below = std::isfinite(min);
  const bool bounded_above = std::isfinite(max);
  if (bounded_below && bounded_above)
    return std::string("in ") + (min_exclusive ? "(" : "[") + format_number(min) + ", " +
           format_number(max) + (max_exclusive ? ")" : "]");
  if (bounded_below) return (min_exclusive ? "> " : ">= ") + format_number(min);
  if (bounded_above) return (max_exclusive ? "< " : "<= ") + format_number(max);
  return "a finite number";
}

namespace {
template <class T>
T checked(const Settings& s, const std::string& key, T value, const Range& range) {
  if (!range.contains(value))
    s.fail(key, "must be " + range.describe() + ", got " + format_number(value));
  return value;
}
}  // namespace

double Settings::required_in_range(const std::string& key, const Range& range) const {
  return checked(*this, key, required<double>(key), range);
}

double Settings::get_in_range(const std::string& key, double default_value,
                              const Range& range) const {
  return checked(*this, key, get<double>(key, default_value), range);
}

namespace {
Range int_range(int min, int max) {
  return max == std::numeric_limits<int>::max() ? Range::at_least(min) : Range::closed(min, max);
}
}  // namespace

int Settings::required_int_in_range(const std::string& key, int min, int max) const {
  return checked(*this, key, required<int>(key), int_range(min, max));
}

int Settings::get_int_in_range(const std::string& key, int default_value, int min, int max) const {
  return checked(*this, key, get<int>(key, default_value), int_range(min, max));
}

namespace {
std::string checked_choice(const Settings& s, const std::string& key, const std::string& value,
                           const std::vector<std::string>& choices) {
  for (const auto& choice : choices)
    if (choice == value) return value;
  s.fail(key, "'" + value + "' is not one of: " + join(choices) + did_you_mean(value, choices));
}
}  // namespace

std::string Settings::required_choice(const std::string& key,
                                      const std::vector<std::string>& choices) const {
  return checked_choice(*this, key, required<std::string>(key), choices);
}

std::string Settings::get_name(const std::string& key, const std::string& default_value) const {
  const std::string name = get<std::string>(key, default_value);
  const bool plain =
      !name.empty() && name.size() <= 100 && name.front() != '.' && name.front() != '-' &&
      std::all_of(name.begin(), name.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
      });
  if (!plain)
    fail(key, "'" + name +
                  "' is not a plain name: use letters, digits, '_', '-' and '.' (not first), at "
                  "most 100 characters; it names files in the solver's working directory");
  return name;
}

std::string Settings::get_choice(const std::string& key, const std::string& default_value,
                                 const std::vector<std::string>& choices) const {
  return checked_choice(*this, key, get<std::string>(key, default_value), choices);
}

Settings Settings::child(const std::string& key) const {
  YAML::Node value = lookup(key);
  if (!value.IsDefined() || value.IsNull())
    fail("", "missing required section '" + key_path(key) + "'" + misspelling_hint(key));
  if (!value.IsMap()) fail(key, "expected a mapping of keys");
  return Settings(document_, value, key_path(key));
}

Settings Settings::child_or_empty(const std::string& key) const {
  if (has(key)) return child(key);
  YAML::Node empty(YAML::NodeType::Map);
  return Settings(document_, empty, key_path(key));
}

std::vector<Settings> Settings::list(const std::string& key) const {
  YAML::Node value = lookup(key);
  if (!value.IsDefined() || value.IsNull())
    fail("", "missing required list '" + key_path(key) + "'" + misspelling_hint(key));
  if (!value.IsSequence()) fail(key, "expected a list");
  std::vector<Settings> out;
  for (std::size_t i = 0; i < value.size(); ++i) {
    YAML::Node item = value[i];
    const std::string item_path = key_path(key) + "[" + std::to_string(i) + "]";
    if (!item.IsMap())
      throw CaseError(location(document_->file, item.Mark()) + ": '" + item_path +
                      "': expected a mapping of keys");
    out.push_back(Settings(document_, item, item_path));
  }
  return out;
}

void Settings::check_unused_keys() const {
  for (const auto& mapping : document_->mappings) {
    const std::vector<std::string> known(mapping.known_keys.begin(), mapping.known_keys.end());
    for (const auto& entry : mapping.node) {
      const std::string key = entry.first.as<std::string>();
      if (mapping.known_keys.count(key)) continue;
      const std::string name = mapping.path.empty() ? key : mapping.path + "." + key;
      throw CaseError(location(document_->file, entry.first.Mark()) + ": unknown key '" + name +
                      "'" + did_you_mean(key, known) + " (valid here: " + join(known) + ")");
    }
  }
}

}  // namespace cocopp

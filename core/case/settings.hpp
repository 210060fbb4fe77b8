#pragma once
// Settings: one mapping of a case file (YAML or JSON), read key by key by the component it
// configures. Every read records the key as valid, so that after all components are built
// `check_unused_keys()` can report typos with the file, line, key path and the nearest valid key.
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace cocopp {

/// An error in a case file or a solver input file; the message names file, line and key path.
class CaseError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The allowed values of a number, with a readable description for messages.
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  bool max_exclusive = false;

  static Range any() { return {}; }
  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true}; }
  static Range non_negative() { return at_least(0.0); }
  static Range at_least(double min) { return {min, std::numeric_limits<double>::infinity()}; }
  /// [min, max]
  static Range closed(double min, double max) { return {min, max}; }
  /// A timeout in seconds: (0, 1e7]. Beyond some 1e9 s the deadline arithmetic of the clocks
  /// overflows and every wait would fail at once; 1e7 s is 116 days.
  static Range timeout() { return {0.0, 1e7, true}; }

  bool contains(double value) const;
  /// ">= 0", "> 0", "in (0, 2]"
  std::string describe() const;
};

class Settings {
 public:
  /// A case file larger than this is refused before it is parsed.
  static constexpr std::size_t kMaxCaseFileBytes = std::size_t(16) << 20;
  /// Parse a YAML or JSON file. Throws CaseError on a syntax error (with file and line), and on
  /// a file that is not a regular one or larger than kMaxCaseFileBytes.
  static Settings load_file(const std::filesystem::path& file);
  /// Parse text (for tests); `file_name` is used in messages.
  static Settings load_string(const std::string& text, const std::string& file_name);

  template <class T>
  T required(const std::string& key) const;
  template <class T>
  T get(const std::string& key, const T& default_value) const;
  /// A number in `range`, required or with a default.
  double required_in_range(const std::string& key, const Range& range) const;
  double get_in_range(const std::string& key, double default_value, const Range& range) const;
  /// An integer in [min, max], required or with a default.
  int required_int_in_range(const std::string& key, int min,
                            int max = std::numeric_limits<int>::max()) const;
  int get_int_in_range(const std::string& key, int default_value, int min,
                       int max = std::numeric_limits<int>::max()) const;
  /// A name that becomes part of file names (a solver's log, its restart files): letters,
  /// digits, '_', '-' and '.', not starting with '.' or '-', at most 100 characters; anything
  /// else (a path like "../x", a space, a control character) is an error at its line.
  std::string get_name(const std::string& key, const std::string& default_value) const;
  /// One of `choices`, required or with a default; error with did-you-mean otherwise.
  std::string required_choice(const std::string& key,
                              const std::vector<std::string>& choices) const;
  std::string get_choice(const std::string& key, const std::string& default_value,
                         const std::vector<std::string>& choices) const;

  bool has(const std::string& key) const;
  /// A nested mapping (required).
  Settings child(const std::string& key) const;
  /// A nested mapping, or an empty mapping at this node's location if absent.
  Settings child_or_empty(const std::string& key) const;
  /// A required sequence of mappings.
  std::vector<Settings> list(const std::string& key) const;

  /// Mark a key as valid without reading it (for keys read by someone else later).
  void allow(const std::string& key) const;

  /// "coupled_solver.model" ("" at the top level).
  const std::string& path() const { return path_; }
  /// "case.yaml:12:5" for this mapping, or for one of its keys.
  std::string where(const std::string& key = "") const;
  /// Directory of the case file: relative paths in settings are resolved against it.
  std::filesystem::path base_directory() const;
  const std::filesystem::path& file() const;

  /// For a required key that is missing: "; is 'number_of_timestep' (line 7) a misspelling of
  /// it?" when a key of this mapping that no reader has asked for is close to it, else "".
  std::string misspelling_hint(const std::string& key) const;

  /// Throw CaseError "file:line:col: key.path: message".
  [[noreturn]] void fail(const std::string& key, const std::string& message) const;

  /// After all components are built: unknown keys anywhere in the file are errors.
  void check_unused_keys() const;

  /// The raw node (for components that parse free-form data).
  const YAML::Node& node() const { return node_; }

 private:
  struct Document;
  Settings(std::shared_ptr<Document> document, YAML::Node node, std::string path);
  YAML::Node lookup(const std::string& key) const;
  std::string key_path(const std::string& key) const;
  template <class T>
  T convert(const YAML::Node& value, const std::string& key) const;

  std::shared_ptr<Document> document_;
  YAML::Node node_;
  std::string path_;
  std::size_t index_ = 0;  ///< this mapping's entry in document_->mappings
};

}  // namespace cocopp

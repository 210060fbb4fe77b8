#pragma once
// Reading a tube solver's own YAML input file, shared by the three tube solvers.
//
// Every read records its key; check_unknown_keys() then reports keys nobody asked for (typos).
// All errors are std::runtime_error with "file:line: key.path: message", where the line is
// the one of the offending key or value (or of the enclosing mapping for a missing key).
#include <yaml-cpp/yaml.h>

#include <Eigen/Dense>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace cocopp::tube {

constexpr double kPi = 3.14159265358979323846;

/// An interval of allowed values for a number, with a readable description for messages.
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  bool max_exclusive = false;

  static Range any() { return {}; }
  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static Range non_negative() { return {0.0, std::numeric_limits<double>::infinity()}; }
  static Range at_least(double min) { return {min, std::numeric_limits<double>::infinity()}; }
  /// [min, max)
  static Range half_open(double min, double max) { return {min, max, false, true}; }

  bool contains(double value) const;
  std::string describe() const;
};

/// One mapping of an input file.
class InputSection {
 public:
  /// Parse a YAML file; throws std::runtime_error (with file and line on syntax errors).
  static InputSection load_file(const std::string& path);
  /// Parse YAML text; `file_name` is used in messages.
  static InputSection load_string(const std::string& text, const std::string& file_name);

  bool has(const std::string& key) const;

  double number(const std::string& key, const Range& range = Range::any()) const;
  double number_or(const std::string& key, double default_value,
                   const Range& range = Range::any()) const;
  int integer(const std::string& key, int min = std::numeric_limits<int>::min()) const;
  int integer_or(const std::string& key, int default_value,
                 int min = std::numeric_limits<int>::min()) const;
  std::string text_or(const std::string& key, const std::string& default_value) const;
  /// One of `choices` (required).
  std::string choice(const std::string& key, const std::vector<std::string>& choices) const;
  std::string choice_or(const std::string& key, const std::string& default_value,
                        const std::vector<std::string>& choices) const;

  /// A nested mapping (required).
  InputSection section(const std::string& key) const;
  /// A nested mapping, or an empty one if the key is absent.
  InputSection section_or_empty(const std::string& key) const;

  /// Throw for any key of this mapping and its nested mappings that was never read.
  void check_unknown_keys() const;

  /// Throw std::runtime_error "file:line: key.path: message" (line of the key if present).
  [[noreturn]] void fail(const std::string& key, const std::string& message) const;

  const std::string& file() const;

 private:
  struct State;
  explicit InputSection(std::shared_ptr<State> state);
  YAML::Node lookup(const std::string& key) const;
  void remember(const std::string& key) const;          ///< record the key as valid
  YAML::Node value_node(const std::string& key) const;  ///< lookup + remember
  YAML::Node require(const std::string& key) const;
  std::string location(const YAML::Mark& mark) const;
  std::string key_path(const std::string& key) const;

  std::shared_ptr<State> state_;
};

/// Geometry shared by the three tube solvers (keys `length`, `diameter`, `cells`).
struct TubeGeometry {
  double length = 0.0;
  double diameter = 0.0;
  int cells = 0;

  double radius() const { return 0.5 * diameter; }
  double cell_size() const { return length / cells; }
  /// Cross-section at rest, pi d^2 / 4.
  double area() const;
  /// Cell centres z_i = -l/2 + dz/2 + i dz, i = 0..m-1 (the tube is centred on z = 0).
  Eigen::VectorXd cell_centres() const;

  static TubeGeometry read(const InputSection& input);
};

/// `output: {interval: N, directory: dir}`; interval 0 writes nothing.
struct OutputSettings {
  int interval = 0;
  std::string directory = "output";

  bool due(int step) const { return interval > 0 && step % interval == 0; }
  static OutputSettings read(const InputSection& input);
};

}  // namespace cocopp::tube

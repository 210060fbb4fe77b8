#include "solver_wrappers/tube/tube_input.hpp"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

namespace cocopp::tube {

namespace {

std::string format_number(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

std::string join(const std::vector<std::string>& words) {
  std::string joined;
  for (const auto& word : words) joined += (joined.empty() ? "" : ", ") + word;
  return joined;
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
  if (bounded_below && bounded_above) {
    return std::string("in ") + (min_exclusive ? "(" : "[") + format_number(min) + ", " +
           format_number(max) + (max_exclusive ? ")" : "]");
  }
  if (bounded_below) return (min_exclusive ? "> " : ">= ") + format_number(min);
  if (bounded_above) return (max_exclusive ? "< " : "<= ") + format_number(max);
  return "a finite number";
}

// The file name, the mapping, its key path and the keys read so far. Nested sections are kept
// so that check_unknown_keys() can walk the whole file.
struct InputSection::State {
  std::string file;
  YAML::Node node;
  std::string path;
  std::set<std::string> used_keys;
  std::vector<std::shared_ptr<State>> children;
};

InputSection::InputSection(std::shared_ptr<State> state) : state_(std::move(state)) {}

InputSection InputSection::load_string(const std::string& text, const std::string& file_name) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& error) {
    throw std::runtime_error(file_name + ":" + std::to_string(error.mark.line + 1) +
                             ": YAML syntax error: " + error.msg);
  }
  if (root.IsNull()) root = YAML::Node(YAML::NodeType::Map);
  if (!root.IsMap()) {
    throw std::runtime_error(file_name + ":" + std::to_string(root.Mark().line + 1) +
                             ": the input file must be a mapping of keys to values");
  }
  auto state = std::make_shared<State>();
  state->file = file_name;
  state->node = root;
  return InputSection(state);
}

InputSection InputSection::load_file(const std::string& path) {
  std::ifstream stream(path);
  if (!stream) throw std::runtime_error(path + ": cannot open the input file");
  std::ostringstream text;
  text << stream.rdbuf();
  return load_string(text.str(), path);
}

const std::string& InputSection::file() const {
  return state_->file;
}

std::string InputSection::location(const YAML::Mark& mark) const {
  // Marks of nodes built in code (absent keys in an empty section) have line -1.
  return state_->file + ":" + std::to_string(std::max(mark.line, 0) + 1);
}

std::string InputSection::key_path(const std::string& key) const {
  return state_->path.empty() ? key : state_->path + "." + key;
}

void InputSection::fail(const std::string& key, const std::string& message) const {
  const YAML::Node value = lookup(key);
  const YAML::Mark mark = value ? value.Mark() : state_->node.Mark();
  throw std::runtime_error(location(mark) + ": " + key_path(key) + ": " + message);
}

// Read through a const node: yaml-cpp's non-const operator[] may insert the missing key.
YAML::Node InputSection::lookup(const std::string& key) const {
  const YAML::Node& node = state_->node;
  return node[key];
}

void InputSection::remember(const std::string& key) const {
  state_->used_keys.insert(key);
}

bool InputSection::has(const std::string& key) const {
  return static_cast<bool>(lookup(key));
}

YAML::Node InputSection::value_node(const std::string& key) const {
  remember(key);
  return lookup(key);
}

YAML::Node InputSection::require(const std::string& key) const {
  const YAML::Node value = value_node(key);
  if (!value) fail(key, "missing required key");
  if (value.IsNull()) fail(key, "no value given");
  return value;
}

double InputSection::number(const std::string& key, const Range& range) const {
  const YAML::Node value = require(key);
  double number = 0.0;
  if (!value.IsScalar() || !YAML::convert<double>::decode(value, number)) {
    fail(key, "expected a number, got '" + YAML::Dump(value) + "'");
  }
  if (!std::isfinite(number)) fail(key, "expected a finite number");
  if (!range.contains(number)) {
    fail(key, "value " + format_number(number) + " out of range: must be " + range.describe());
  }
  return number;
}

double InputSection::number_or(const std::string& key, double default_value,
                               const Range& range) const {
  if (!has(key)) {
    remember(key);
    return default_value;
  }
  return number(key, range);
}

int InputSection::integer(const std::string& key, int min) const {
  const YAML::Node value = require(key);
  int number = 0;
  if (!value.IsScalar() || !YAML::convert<int>::decode(value, number)) {
    fail(key, "expected an integer, got '" + YAML::Dump(value) + "'");
  }
  if (number < min) {
    fail(key,
         "value " + std::to_string(number) + " out of range: must be >= " + std::to_string(min));
  }
  return number;
}

int InputSection::integer_or(const std::string& key, int default_value, int min) const {
  if (!has(key)) {
    remember(key);
    return default_value;
  }
  return integer(key, min);
}

std::string InputSection::text_or(const std::string& key, const std::string& default_value) const {
  if (!has(key)) {
    remember(key);
    return default_value;
  }
  const YAML::Node value = value_node(key);
  if (!value.IsScalar() || value.Scalar().empty()) fail(key, "expected a non-empty string");
  return value.Scalar();
}

std::string InputSection::choice(const std::string& key,
                                 const std::vector<std::string>& choices) const {
  const YAML::Node value = require(key);
  if (value.IsScalar()) {
    for (const auto& candidate : choices) {
      if (value.Scalar() == candidate) return candidate;
    }
  }
  fail(key, "expected one of " + join(choices) + ", got '" + YAML::Dump(value) + "'");
}

std::string InputSection::choice_or(const std::string& key, const std::string& default_value,
                                    const std::vector<std::string>& choices) const {
  if (!has(key)) {
    remember(key);
    return default_value;
  }
  return choice(key, choices);
}

InputSection InputSection::section(const std::string& key) const {
  const YAML::Node value = require(key);
  if (!value.IsMap()) fail(key, "expected a mapping of keys to values");
  auto child = std::make_shared<State>();
  child->file = state_->file;
  child->node = value;
  child->path = key_path(key);
  state_->children.push_back(child);
  return InputSection(child);
}

InputSection InputSection::section_or_empty(const std::string& key) const {
  if (has(key)) return section(key);
  remember(key);
  auto child = std::make_shared<State>();
  child->file = state_->file;
  child->node = YAML::Node(YAML::NodeType::Map);
  child->path = key_path(key);
  state_->children.push_back(child);
  return InputSection(child);
}

void InputSection::check_unknown_keys() const {
  for (const auto& entry : state_->node) {
    const std::string key = entry.first.Scalar();  // "" for a (rare) non-scalar key
    if (state_->used_keys.count(key) == 0) {
      std::vector<std::string> known(state_->used_keys.begin(), state_->used_keys.end());
      throw std::runtime_error(location(entry.first.Mark()) + ": " + key_path(key) +
                               ": unknown key (valid keys here: " + join(known) + ")");
    }
  }
  for (const auto& child : state_->children) InputSection(child).check_unknown_keys();
}

double TubeGeometry::area() const {
  return kPi * diameter * diameter / 4.0;
}

Eigen::VectorXd TubeGeometry::cell_centres() const {
  const double dz = cell_size();
  Eigen::VectorXd z(cells);
  for (int i = 0; i < cells; ++i) z[i] = -length / 2.0 + dz / 2.0 + i * dz;
  return z;
}

TubeGeometry TubeGeometry::read(const InputSection& input) {
  TubeGeometry geometry;
  geometry.length = input.number("length", Range::positive());
  geometry.diameter = input.number("diameter", Range::positive());
  // Two cells at least: the boundary rows extrapolate from the two cells next to each end.
  geometry.cells = input.integer("cells", 2);
  return geometry;
}

OutputSettings OutputSettings::read(const InputSection& input) {
  const InputSection output = input.section_or_empty("output");
  OutputSettings settings;
  settings.interval = output.integer_or("interval", settings.interval, 0);
  settings.directory = output.text_or("directory", settings.directory);
  return settings;
}

}  // namespace cocopp::tube

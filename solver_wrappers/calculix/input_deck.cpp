#include "solver_wrappers/calculix/input_deck.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <fstream>

namespace cocopp::calculix {

namespace {

constexpr int kMaxIncludeDepth = 20;

std::string trim(const std::string& text) {
  const auto begin = text.find_first_not_of(" \t\r\n");
  if (begin == std::string::npos) return "";
  const auto end = text.find_last_not_of(" \t\r\n");
  return text.substr(begin, end - begin + 1);
}

bool is_keyword_line(const std::string& line) {
  return line.size() >= 1 && line[0] == '*' && (line.size() < 2 || line[1] != '*');
}

bool is_comment_line(const std::string& line) {
  return line.size() >= 2 && line[0] == '*' && line[1] == '*';
}

/// Nodes per element of the types ccx knows, by the type name's leading part.
int nodes_per_element(const std::string& type) {
  static const std::vector<std::pair<std::string, int>> table = {
      {"C3D20", 20}, {"C3D15", 15}, {"C3D10", 10}, {"C3D8", 8}, {"C3D6", 6}, {"C3D4", 4},
      {"CPE8", 8},   {"CPS8", 8},   {"CAX8", 8},   {"CPE6", 6}, {"CPS6", 6}, {"CAX6", 6},
      {"CPE4", 4},   {"CPS4", 4},   {"CAX4", 4},   {"CPE3", 3}, {"CPS3", 3}, {"CAX3", 3},
      {"S8", 8},     {"S6", 6},     {"S4", 4},     {"S3", 3},   {"B32", 3},  {"B31", 2},
      {"T3D2", 2},   {"T3D3", 3}};
  for (const auto& [prefix, count] : table)
    if (type.rfind(prefix, 0) == 0) return count;
  return -1;  // unknown: one data line per element
}

void read_lines(const std::filesystem::path& file, const std::filesystem::path& run_directory,
                const std::string& included_from, int depth, std::vector<DeckLine>& lines) {
  if (depth > kMaxIncludeDepth)
    throw DeckError(included_from + ": *INCLUDE nested more than " +
                    std::to_string(kMaxIncludeDepth) + " deep (an include cycle?)");
  std::ifstream in(file);
  if (!in)
    throw DeckError((included_from.empty() ? "" : included_from + ": ") + "cannot read " +
                    file.string());
  std::string text;
  int number = 0;
  while (std::getline(in, text)) {
    ++number;
    const std::string line = trim(text);
    if (line.empty() || is_comment_line(line)) continue;
    const std::string where = file.filename().string() + ":" + std::to_string(number);
    if (is_keyword_line(line) && upper(split_commas(line)[0]) == "*INCLUDE") {
      std::string input;
      for (const auto& field : split_commas(line)) {
        const auto equals = field.find('=');
        if (equals != std::string::npos && upper(trim(field.substr(0, equals))) == "INPUT")
          input = trim(field.substr(equals + 1));
      }
      if (input.empty()) throw DeckError(where + ": *INCLUDE without INPUT=");
      if (input.size() >= 2 && input.front() == '"' && input.back() == '"')
        input = input.substr(1, input.size() - 2);
      read_lines(run_directory / input, run_directory, where, depth + 1, lines);
      continue;
    }
    lines.push_back({line, where});
  }
}

double parse_number(const std::string& field, const std::string& where) {
  std::string text = field;
  std::replace(text.begin(), text.end(), 'd', 'e');  // Fortran 1.0D3
  std::replace(text.begin(), text.end(), 'D', 'e');
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE)
    throw DeckError(where + ": '" + field + "' is not a number");
  return value;
}

std::int64_t parse_id(const std::string& field, const std::string& where) {
  char* end = nullptr;
  const long long value = std::strtoll(field.c_str(), &end, 10);
  if (field.empty() || end != field.c_str() + field.size())
    throw DeckError(where + ": '" + field + "' is not an integer");
  return value;
}

bool is_integer(const std::string& field) {
  return !field.empty() && std::all_of(field.begin(), field.end(), [](char c) {
    return std::isdigit(static_cast<unsigned char>(c)) != 0 || c == '-' || c == '+';
  });
}

}  // namespace

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  for (;;) {
    const auto comma = text.find(',', start);
    fields.push_back(trim(text.substr(start, comma - start)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  // A trailing comma continues a list on the next line: it adds no field.
  if (!fields.empty() && fields.back().empty()) fields.pop_back();
  return fields;
}

std::string upper(std::string text) {
  for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

/// A keyword line with its parameters and data lines.
struct InputDeck::Card {
  std::string keyword;                            ///< upper case, without '*', e.g. "SOLID SECTION"
  std::map<std::string, std::string> parameters;  ///< upper-case keys; values as written
  std::vector<DeckLine> data;
  DeckLine line;

  bool has(const std::string& key) const { return parameters.count(key) != 0; }
  std::string parameter(const std::string& key) const {
    const auto found = parameters.find(key);
    if (found == parameters.end())
      throw DeckError(line.where + ": *" + keyword + " needs the parameter " + key + "=");
    return found->second;
  }
};

Eigen::Matrix3d NodalTransform::axes_at(const Eigen::Vector3d& point) const {
  Eigen::Matrix3d axes;
  if (type == 'R') {
    const Eigen::Vector3d x = a.normalized();
    const Eigen::Vector3d y = (b - b.dot(x) * x).normalized();
    axes.row(0) = x;
    axes.row(1) = y;
    axes.row(2) = x.cross(y);
    return axes;
  }
  // Cylindrical: x' radial, y' tangential, z' along the axis from a to b.
  const Eigen::Vector3d z = (b - a).normalized();
  Eigen::Vector3d radial = point - a;
  radial -= radial.dot(z) * z;
  if (radial.norm() == 0.0)
    throw DeckError("a node with a cylindrical *TRANSFORM lies on the cylinder's axis");
  const Eigen::Vector3d x = radial.normalized();
  axes.row(0) = x;
  axes.row(1) = z.cross(x);
  axes.row(2) = z;
  return axes;
}

InputDeck InputDeck::read(const std::filesystem::path& file,
                          const std::filesystem::path& run_directory) {
  std::vector<DeckLine> lines;
  read_lines(file, run_directory, "", 0, lines);
  std::vector<Card> cards;
  for (const auto& line : lines) {
    if (is_keyword_line(line.text)) {
      Card card;
      card.line = line;
      const auto fields = split_commas(line.text);
      card.keyword = upper(trim(fields[0].substr(1)));
      for (std::size_t i = 1; i < fields.size(); ++i) {
        const auto equals = fields[i].find('=');
        const std::string key = upper(trim(fields[i].substr(0, equals)));
        card.parameters[key] =
            equals == std::string::npos ? "" : trim(fields[i].substr(equals + 1));
      }
      cards.push_back(std::move(card));
    } else {
      if (cards.empty()) throw DeckError(line.where + ": data line before the first keyword");
      cards.back().data.push_back(line);
    }
  }
  InputDeck deck;
  deck.file_ = file.string();
  deck.interpret(cards);
  return deck;
}

void InputDeck::interpret(const std::vector<Card>& cards) {
  enum class Part { kModel, kStep, kAfterStep } part = Part::kModel;
  for (const auto& card : cards) {
    if (card.keyword == "RESTART")
      throw DeckError(card.line.where +
                      ": *RESTART: the calculix wrapper writes and reads the restart files "
                      "itself (to reset each coupling iteration); remove this card");
    if (card.keyword == "STEP") {
      if (part != Part::kModel)
        throw DeckError(card.line.where +
                        ": a second *STEP: give one step; the wrapper repeats it for every "
                        "coupling time step, with the loads of each coupling iteration");
      part = Part::kStep;
      nonlinear_geometry_ = card.has("NLGEOM");
    }
    if (card.keyword == "END STEP" && part == Part::kModel)
      throw DeckError(card.line.where + ": *END STEP before any *STEP");
    if (part == Part::kModel) keywords_.insert(card.keyword);
    auto& target = part == Part::kModel ? model_definition_ : step_;
    if (part == Part::kAfterStep)
      throw DeckError(card.line.where + ": *" + card.keyword +
                      " after *END STEP: the deck must end with its one step");
    target.push_back(card.line);
    target.insert(target.end(), card.data.begin(), card.data.end());
    if (card.keyword == "END STEP") part = Part::kAfterStep;

    if (card.keyword == "NODE") read_nodes(card);
    if (card.keyword == "ELEMENT") read_elements(card);
    if (card.keyword == "NSET") read_set(card, true);
    if (card.keyword == "ELSET") read_set(card, false);
    if (card.keyword == "SURFACE") read_surface(card);
    if (card.keyword == "TRANSFORM") read_transform(card);
    if (card.keyword == "SOLID SECTION") read_solid_section(card);
    if (part == Part::kStep && procedure_.empty() &&
        (card.keyword == "STATIC" || card.keyword == "DYNAMIC" || card.keyword == "VISCO"))
      read_procedure(card);
  }
  if (part == Part::kModel)
    throw DeckError(file_ +
                    ": no *STEP: the deck must end with the step to repeat every time step");
  if (part == Part::kStep) throw DeckError(file_ + ": the *STEP has no *END STEP");
  if (procedure_.empty())
    throw DeckError(step_.front().where +
                    ": the step has no *STATIC or *DYNAMIC procedure (the wrapper supports "
                    "static, dynamic and visco steps)");
}

void InputDeck::read_nodes(const Card& card) {
  std::vector<std::int64_t>* set =
      card.has("NSET") ? &node_sets_[upper(card.parameter("NSET"))] : nullptr;
  for (const auto& line : card.data) {
    const auto fields = split_commas(line.text);
    if (fields.empty() || fields.size() > 4)
      throw DeckError(line.where + ": *NODE data: expected 'id, x, y, z'");
    const std::int64_t id = parse_id(fields[0], line.where);
    Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
    for (std::size_t i = 1; i < fields.size(); ++i)
      xyz[static_cast<Eigen::Index>(i - 1)] = parse_number(fields[i], line.where);
    nodes_[id] = xyz;
    if (set) set->push_back(id);
  }
}

void InputDeck::read_elements(const Card& card) {
  const std::string type = upper(card.parameter("TYPE"));
  const int count = nodes_per_element(type);
  std::vector<std::int64_t>* set =
      card.has("ELSET") ? &element_sets_[upper(card.parameter("ELSET"))] : nullptr;
  std::vector<std::int64_t> entries;
  const DeckLine* first_line = nullptr;
  for (const auto& line : card.data) {
    if (entries.empty()) first_line = &line;
    for (const auto& field : split_commas(line.text))
      entries.push_back(parse_id(field, line.where));
    // Long elements continue on the next line until all their nodes are there.
    if (count > 0 && static_cast<int>(entries.size()) < count + 1) continue;
    if (count > 0 && static_cast<int>(entries.size()) > count + 1)
      throw DeckError(first_line->where + ": element of type " + type + " with " +
                      std::to_string(entries.size() - 1) + " nodes (" + std::to_string(count) +
                      " expected)");
    elements_[entries[0]] = Element{type, {entries.begin() + 1, entries.end()}};
    if (set) set->push_back(entries[0]);
    entries.clear();
  }
  if (!entries.empty())
    throw DeckError(first_line->where + ": the last element of type " + type + " has " +
                    std::to_string(entries.size() - 1) + " nodes (" + std::to_string(count) +
                    " expected)");
}

void InputDeck::read_set(const Card& card, bool nodes) {
  const std::string key = nodes ? "NSET" : "ELSET";
  auto& sets = nodes ? node_sets_ : element_sets_;
  auto& set = sets[upper(card.parameter(key))];
  const bool generate = card.has("GENERATE");
  for (const auto& line : card.data) {
    const auto fields = split_commas(line.text);
    if (generate) {
      if (fields.size() < 2 || fields.size() > 3)
        throw DeckError(line.where + ": *" + card.keyword +
                        ", GENERATE: expected 'first, last[, step]'");
      const std::int64_t first = parse_id(fields[0], line.where);
      const std::int64_t last = parse_id(fields[1], line.where);
      const std::int64_t step = fields.size() == 3 ? parse_id(fields[2], line.where) : 1;
      if (step <= 0) throw DeckError(line.where + ": GENERATE step must be positive");
      for (std::int64_t id = first; id <= last; id += step) set.push_back(id);
      continue;
    }
    for (const auto& field : fields) {
      if (is_integer(field)) {
        set.push_back(parse_id(field, line.where));
        continue;
      }
      const auto other = sets.find(upper(field));
      if (other == sets.end())
        throw DeckError(line.where + ": *" + card.keyword + ": set " + field + " is not defined");
      set.insert(set.end(), other->second.begin(), other->second.end());
    }
  }
}

void InputDeck::read_surface(const Card& card) {
  const std::string name = upper(card.parameter("NAME"));
  if (card.has("TYPE") && upper(card.parameter("TYPE")) != "ELEMENT") return;  // node surfaces
  auto& surface = surfaces_[name];
  for (const auto& line : card.data) {
    const auto fields = split_commas(line.text);
    if (fields.size() != 2 || upper(fields[1]).rfind('S', 0) != 0)
      throw DeckError(line.where + ": *SURFACE data: expected 'element or element set, S<face>'");
    const int face = static_cast<int>(parse_id(fields[1].substr(1), line.where));
    if (is_integer(fields[0])) {
      surface.push_back({parse_id(fields[0], line.where), face});
      continue;
    }
    const auto set = element_sets_.find(upper(fields[0]));
    if (set == element_sets_.end())
      throw DeckError(line.where + ": *SURFACE: element set " + fields[0] + " is not defined");
    for (const auto element : set->second) surface.push_back({element, face});
  }
}

void InputDeck::read_transform(const Card& card) {
  const std::string type = card.has("TYPE") ? upper(card.parameter("TYPE")) : "R";
  if (type != "R" && type != "C")
    throw DeckError(card.line.where + ": *TRANSFORM TYPE=" + type + " (R or C expected)");
  if (card.data.size() != 1)
    throw DeckError(card.line.where + ": *TRANSFORM needs one data line with 6 coordinates");
  const auto fields = split_commas(card.data[0].text);
  if (fields.size() != 6)
    throw DeckError(card.data[0].where + ": *TRANSFORM data: expected 6 coordinates");
  NodalTransform transform{type[0], {}, {}};
  for (int i = 0; i < 3; ++i) {
    transform.a[i] = parse_number(fields[static_cast<std::size_t>(i)], card.data[0].where);
    transform.b[i] = parse_number(fields[static_cast<std::size_t>(i + 3)], card.data[0].where);
  }
  for (const auto node : node_set(card.parameter("NSET"))) transforms_[node] = transform;
}

void InputDeck::read_solid_section(const Card& card) {
  if (card.data.empty()) return;
  const auto fields = split_commas(card.data[0].text);
  if (fields.empty()) return;
  const double thickness = parse_number(fields[0], card.data[0].where);
  const auto set = element_sets_.find(upper(card.parameter("ELSET")));
  if (set == element_sets_.end())
    throw DeckError(card.line.where + ": *SOLID SECTION: element set " + card.parameter("ELSET") +
                    " is not defined");
  for (const auto element : set->second) thicknesses_[element] = thickness;
}

void InputDeck::read_procedure(const Card& card) {
  procedure_ = card.keyword;
  step_time_period_ = 1.0;  // ccx's default
  initial_increment_ = step_time_period_;
  procedure_line_ = step_.size() - card.data.size() - 1;  // the card and its data are in step_
  if (card.data.empty()) return;
  procedure_data_line_ = step_.size() - card.data.size();  // the card and its data are in step_
  const auto fields = split_commas(card.data[0].text);
  if (fields.size() >= 2 && !fields[1].empty())
    step_time_period_ = parse_number(fields[1], card.data[0].where);
  initial_increment_ = !fields.empty() && !fields[0].empty()
                           ? parse_number(fields[0], card.data[0].where)
                           : step_time_period_;
}

const Eigen::Vector3d& InputDeck::node(std::int64_t id) const {
  const auto found = nodes_.find(id);
  if (found == nodes_.end())
    throw DeckError(file_ + ": node " + std::to_string(id) + " is used but not defined");
  return found->second;
}

const Element& InputDeck::element(std::int64_t id) const {
  const auto found = elements_.find(id);
  if (found == elements_.end())
    throw DeckError(file_ + ": element " + std::to_string(id) + " is used but not defined");
  return found->second;
}

const std::vector<std::int64_t>& InputDeck::node_set(const std::string& name) const {
  const auto found = node_sets_.find(upper(name));
  if (found == node_sets_.end())
    throw DeckError(file_ + ": no node set " + name + " (*NSET or *NODE, NSET=)");
  return found->second;
}

const std::vector<ElementFace>& InputDeck::surface(const std::string& name) const {
  const auto found = surfaces_.find(upper(name));
  if (found == surfaces_.end())
    throw DeckError(file_ + ": no element-face surface " + name + " (*SURFACE, NAME=" + name +
                    ", TYPE=ELEMENT)");
  return found->second;
}

const NodalTransform* InputDeck::transform(std::int64_t node) const {
  const auto found = transforms_.find(node);
  return found == transforms_.end() ? nullptr : &found->second;
}

double InputDeck::thickness(std::int64_t element) const {
  const auto found = thicknesses_.find(element);
  return found == thicknesses_.end() ? 1.0 : found->second;
}

}  // namespace cocopp::calculix

#pragma once
// InputDeck: what the CalculiX wrapper needs from a user's ccx input deck (.inp): the mesh
// (nodes, elements), node and element sets, element-face surfaces, nodal coordinate transforms
// and section thicknesses of plane elements; and the deck split into its model definition
// (everything before the first *STEP) and its one step (*STEP ... *END STEP), which the
// wrapper repeats for every coupling time step. *INCLUDE files are followed (relative to the
// directory ccx runs in, as ccx does). Errors name the file and line.
#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace cocopp::calculix {

/// A malformed deck, or one the wrapper cannot use; the message names file and line.
class DeckError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Element {
  std::string type;  ///< upper case, e.g. "C3D20R"
  std::vector<std::int64_t> nodes;
};

/// One face of an element: face number 1.. as in the deck's "S3".
struct ElementFace {
  std::int64_t element;
  int face;
};

/// *TRANSFORM: a nodal coordinate system for loads and boundary conditions.
struct NodalTransform {
  char type;  ///< 'R' rectangular, 'C' cylindrical
  Eigen::Vector3d a;
  Eigen::Vector3d b;
  /// Rows: the local axes (x', y', z') in global coordinates at `point`.
  Eigen::Matrix3d axes_at(const Eigen::Vector3d& point) const;
};

/// A source line of the deck (after *INCLUDE expansion), for messages.
struct DeckLine {
  std::string text;
  std::string where;  ///< "deck.inp:12"
};

class InputDeck {
 public:
  /// Read `file`; `run_directory` is where ccx runs (*INCLUDE paths are relative to it).
  static InputDeck read(const std::filesystem::path& file,
                        const std::filesystem::path& run_directory);

  const std::map<std::int64_t, Eigen::Vector3d>& nodes() const { return nodes_; }
  const std::map<std::int64_t, Element>& elements() const { return elements_; }
  const Eigen::Vector3d& node(std::int64_t id) const;
  const Element& element(std::int64_t id) const;
  /// Node ids of a node set in deck order (names are case-insensitive, as in ccx).
  const std::vector<std::int64_t>& node_set(const std::string& name) const;
  const std::vector<ElementFace>& surface(const std::string& name) const;
  /// The transform of a node, or nullptr.
  const NodalTransform* transform(std::int64_t node) const;
  /// Thickness of a plane element (the *SOLID SECTION's first data value; 1 if not given).
  double thickness(std::int64_t element) const;

  /// The model definition and the step, as lines (includes expanded).
  const std::vector<DeckLine>& model_definition() const { return model_definition_; }
  const std::vector<DeckLine>& step() const { return step_; }
  /// The step's procedure, e.g. "STATIC" or "DYNAMIC", and its time period (0 if not given).
  const std::string& procedure() const { return procedure_; }
  double step_time_period() const { return step_time_period_; }
  /// Index in step() of the procedure card (*STATIC, *DYNAMIC, ...).
  std::size_t procedure_line() const { return procedure_line_; }
  /// Index in step() of the procedure's first data line (initial increment, period, ...), if
  /// the deck gives one.
  std::optional<std::size_t> procedure_data_line() const { return procedure_data_line_; }
  /// The procedure's initial increment (its data line's first value; the time period if not
  /// given, as ccx does).
  double initial_increment() const { return initial_increment_; }
  /// Whether the *STEP card has NLGEOM: ccx applies pressures on the deformed faces.
  bool nonlinear_geometry() const { return nonlinear_geometry_; }
  /// Whether the model definition has a card with this keyword (upper case, e.g. "PLASTIC").
  bool has_keyword(const std::string& keyword) const { return keywords_.count(keyword) != 0; }

 private:
  struct Card;
  void interpret(const std::vector<Card>& cards);
  void read_nodes(const Card& card);
  void read_elements(const Card& card);
  void read_set(const Card& card, bool nodes);
  void read_surface(const Card& card);
  void read_transform(const Card& card);
  void read_solid_section(const Card& card);
  void read_procedure(const Card& card);

  std::map<std::int64_t, Eigen::Vector3d> nodes_;
  std::map<std::int64_t, Element> elements_;
  std::map<std::string, std::vector<std::int64_t>> node_sets_;
  std::map<std::string, std::vector<std::int64_t>> element_sets_;
  std::map<std::string, std::vector<ElementFace>> surfaces_;
  std::map<std::int64_t, NodalTransform> transforms_;
  std::map<std::int64_t, double> thicknesses_;
  std::vector<DeckLine> model_definition_;
  std::vector<DeckLine> step_;
  std::set<std::string> keywords_;  ///< of the model definition
  std::string procedure_;
  double step_time_period_ = 0.0;
  std::size_t procedure_line_ = 0;
  std::optional<std::size_t> procedure_data_line_;
  double initial_increment_ = 0.0;
  bool nonlinear_geometry_ = false;
  std::string file_;
};

/// The comma-separated fields of a deck line, trimmed (a trailing comma adds none).
std::vector<std::string> split_commas(const std::string& text);

/// Upper case, as ccx compares names and keywords.
std::string upper(std::string text);

}  // namespace cocopp::calculix

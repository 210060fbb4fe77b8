#pragma once
// DisplacementDrive: the calculix wrapper's `interface_drive: displacement`. Where the other
// solver covers the structure's surface (a lubricant film on a wire), the nodes are driven by
// the other solver's wall position instead of loaded by its pressure, and the wrapper returns
// the position that balances the two forces after one Newton step with a local stiffness
// (docs/design/displacement-driven-wire.md):
//   1. plan(): a face is driven when the other solver covers at least half of it; a node when
//      every interface face it belongs to is driven. Its prescribed value in the driven
//      direction is the other solver's wall position at the node (`wall_displacement`, given
//      per drivable node, mapped so that the returned position maps back onto the wall:
//      the mapped wrapper's exact_round_trip; the nodes report whether they were driven).
//   2. write(): *BOUNDARY, OP=NEW with the driven nodes (ccx keeps a prescribed node
//      prescribed in later steps otherwise, and the wire slides), the deck's own *BOUNDARY
//      cards again (OP=NEW dropped them), and the loads as consistent nodal forces, but none
//      in a driven direction (ccx's reaction there is the force the structure takes).
//   3. balance(): per line of driven nodes (a circle about a cylindrical *TRANSFORM's axis: a
//      sector's hoop line; else a node) the traction q along the driven direction that the
//      film gives beyond what the structure takes (the line's nodal imbalance over its nodes'
//      share of a uniform traction); the line moves by q / (K_film + K_structure),
//      K_film = 2 p / gap (a lubricant film's pressure goes as 1 / gap^2) and K_structure the
//      case's `surface_stiffness`. Where a line's share is negative (a serendipity face's
//      corner alone), per face instead: the face's imbalance, nodes moved by their faces'.
//      With a surface compliance (use_compliance()), the lines move together instead:
//      (K_film + K_structure) d = F over the driven lines, K_structure the inverse of their
//      compliance (the other lines loaded), K_film diagonal as above, F the lines' imbalances.
//      With use_reynolds_film(), K_film couples the lines too: a thin film's pressure answers
//      a gap change along the whole film (reynolds_film.hpp), not at the face alone.
// ccx's reactions are the nodal forces only on 3D models: on an axisymmetric (CAX) one they
// are off by up to 53 % (examples/wire_drawing/reaction_probe.py), so the wrapper refuses it.
#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include "core/data/interface.hpp"
#include "solver_wrappers/calculix/input_deck.hpp"
#include "solver_wrappers/calculix/interface_loads.hpp"
#include "solver_wrappers/calculix/surface_compliance.hpp"

namespace cocopp::calculix {

class DisplacementDrive {
 public:
  /// The input variables this mode adds to pressure and traction on the interface faces, and
  /// the one it takes at the drivable nodes.
  static const std::vector<std::string>& face_variables();
  static constexpr const char* kNodeVariable = "wall_displacement";

  /// `interface_nodes`: the nodes whose displacement the wrapper returns; `drivable_nodes`:
  /// those that may be driven (all of the surface's: on a 3D sector, the interface node set
  /// may be one side of it only); `dof`: the driven direction (1..3, in a node's *TRANSFORM
  /// system if it has one); `surface_stiffness`: the structure's stiffness per area against a
  /// push of its surface (Pa/m). Throws DeckError for decks it cannot drive (axisymmetric
  /// elements on the interface, *BOUNDARY inside the step).
  DisplacementDrive(const InputDeck& deck, InterfaceLoads& loads,
                    std::vector<std::int64_t> interface_nodes,
                    std::vector<std::int64_t> drivable_nodes, int dof, double surface_stiffness);

  /// The Newton step takes the structure's stiffness between the driven lines from
  /// `compliance` (times `scale`: above 1 for a body softer than the compliance's, a yielding
  /// one) instead of `surface_stiffness` per line. Every drivable node must be in one of its
  /// lines (throws DeckError naming the first that is not).
  void use_compliance(SurfaceCompliance compliance, double scale);
  /// The film's stiffness between the driven lines from Reynolds' equation on the covered
  /// faces' gaps, fitted to the film's pressure (reynolds_film.hpp), instead of 2 p / gap per
  /// line. Needs the driven nodes in a cylindrical *TRANSFORM (its axis is the film's).
  void use_reynolds_film() { reynolds_film_ = true; }
  /// The film's stiffness between the driven lines from the film's own finite differences
  /// (probed_film.hpp): `file`, which the film writes each step at its first coupling
  /// iteration; it must be this step's (docs/wire-drawing.md, "The film's own sensitivity").
  void use_probed_film(std::filesystem::path file) { probed_film_file_ = std::move(file); }
  /// Append each balance()'s lines to `file` (`drive_log`): a block "# step S iteration K" (and
  /// "reynolds_misfit M" with the Reynolds film), then per driven line one of its nodes, its
  /// axial position, prescribed value, imbalance (N), weight (m^2), the film's local stiffness
  /// 2 p / gap (Pa/m) and its move: what a model of the interface's Jacobian can be checked
  /// against (examples/wire_drawing/drive_pairs.py).
  void log_to(std::filesystem::path file) { log_file_ = std::move(file); }
  /// A new time step: the log's iterations count from 1 again.
  void start_step(int step) {
    log_step_ = step;
    log_iteration_ = 0;
  }
  /// The largest misfit of the Reynolds model to the film's pressure in the last balance().
  double reynolds_misfit() const { return reynolds_misfit_; }

  /// This iteration's inputs (from the wrapper's input interface): one row per interface face,
  /// and the wall displacement one per drivable node. The loads are either the pressure and
  /// the traction (traction may be empty: none) or the force on each face (a total, mapped
  /// conservatively: the structure then takes exactly the other solver's force, and the
  /// film's stiffness takes the face's mean pressure from it).
  struct Inputs {
    Eigen::VectorXd pressure;
    RowMatrix traction;
    RowMatrix force;
    Eigen::VectorXd gap;
    Eigen::VectorXd coverage;
    RowMatrix wall_displacement;
  };
  /// Choose the driven nodes and their values, then, in an NLGEOM step, take the faces where
  /// this iteration puts them: `converged`, the surface nodes' displacement at the last
  /// converged step (global; every face node, both sides of a sector), with each driven
  /// node's driven direction at its prescribed value. The other solver's loads become nodal
  /// forces on those faces, as it computed them on its wall at this iteration's position: a
  /// face left as an earlier step left it, or with one side of a sector moved, takes a force
  /// the other solver never gave.
  void plan(const Inputs& inputs, const NodeDisplacements& converged);
  /// The step's loads file: boundary cards, then the loads (see the header comment).
  void write(std::ostream& out) const;
  /// The interface nodes' displacement to return (one row per interface node, global):
  /// ccx's `displacement`, with the driven direction of driven nodes replaced by the balanced
  /// position; `reaction` holds ccx's RF per drivable node in the nodes' own systems.
  RowMatrix balance(const RowMatrix& displacement, const RowMatrix& reaction) const;

  std::size_t driven_nodes() const { return prescribed_.size(); }
  bool drives(std::int64_t node) const { return prescribed_.count(node) != 0; }
  /// The largest force imbalance per area of the last balance() (Pa), for messages.
  double largest_imbalance() const { return largest_imbalance_; }
  /// The other solver's loads as plan() made them nodal forces (global), driven directions
  /// included: what the structure takes at the coupling's fixed point.
  const std::map<std::int64_t, Eigen::Vector3d>& film_forces() const { return film_forces_; }

 private:
  /// The faces at `converged` with the driven nodes at their prescribed values (plan()).
  void move_faces(const NodeDisplacements& converged);
  /// The driven direction at a node, global.
  Eigen::Vector3d direction(std::int64_t node) const;
  /// The force a unit traction on `face` gives `node` (its shape function's integral there).
  double weight_in(std::int64_t node, std::size_t face) const;
  /// The part of a node's force that `face` gives under a uniform traction on all its faces.
  double share(std::int64_t node, std::size_t face) const;
  /// The film's stiffness per area on `face`: 2 p / gap.
  double film_stiffness(std::size_t face) const;
  /// The driven nodes in groups that move as one: a circle about the axis of their
  /// cylindrical *TRANSFORM (a sector's hoop line, driven alike), else each node alone.
  std::vector<std::vector<std::int64_t>> driven_lines() const;
  /// The move of each driven node after one Newton step on each line's imbalance (empty if a
  /// line's nodes take a negative share of a uniform traction), or on each face's.
  std::map<std::int64_t, double> moves_by_line(
      const std::map<std::int64_t, double>& imbalance) const;
  /// The lines' moves from their forces, weights and film stiffnesses: each line alone, or
  /// all together through the compliance.
  Eigen::VectorXd line_moves(const std::vector<std::vector<std::int64_t>>& lines,
                             const Eigen::VectorXd& force, const Eigen::VectorXd& weight,
                             const Eigen::MatrixXd& film) const;
  void log_lines(const std::vector<std::vector<std::int64_t>>& lines, const Eigen::VectorXd& force,
                 const Eigen::VectorXd& weight, const Eigen::VectorXd& film,
                 const Eigen::VectorXd& move) const;
  /// The film's stiffness between the lines (N/m, the force on line i per move of line j):
  /// Reynolds' equation over each run of driven faces along the axis.
  Eigen::MatrixXd reynolds_film_stiffness(
      const std::vector<std::vector<std::int64_t>>& lines) const;
  /// The same from the film's probe file (use_probed_film()).
  Eigen::MatrixXd probed_film_stiffness(const std::vector<std::vector<std::int64_t>>& lines,
                                        const Eigen::VectorXd& weight,
                                        const Eigen::VectorXd& film) const;
  /// A face the film covers, its extent along the axis.
  struct FilmFace {
    double start, end;
    std::size_t index;
  };
  /// The stiffness one run of touching faces gives (reynolds_film_stiffness()).
  Eigen::MatrixXd film_run_stiffness(const std::vector<FilmFace>& run,
                                     const std::map<std::int64_t, Eigen::Index>& line_of,
                                     Eigen::Index lines) const;
  /// A node's position along the axis of its cylindrical *TRANSFORM (the deck's geometry).
  double axial_position(std::int64_t node) const;
  std::map<std::int64_t, double> moves_by_face(
      const std::map<std::int64_t, double>& imbalance) const;
  std::vector<std::string> model_boundary_cards(const InputDeck& deck) const;

  const InputDeck& deck_;
  InterfaceLoads& loads_;  ///< moved to each iteration's position by plan()
  std::vector<std::int64_t> interface_nodes_, drivable_nodes_;
  int dof_;
  double surface_stiffness_;
  std::optional<SurfaceCompliance> compliance_;
  double compliance_scale_ = 1.0;
  bool reynolds_film_ = false;
  std::filesystem::path probed_film_file_;  ///< empty: not probed
  std::filesystem::path log_file_;
  int log_step_ = 0;
  mutable int log_iteration_ = 0;
  mutable double reynolds_misfit_ = 0.0;
  std::vector<std::string> model_boundary_;
  /// Per node: the faces it belongs to.
  std::map<std::int64_t, std::vector<std::size_t>> faces_of_;

  // From plan().
  Inputs inputs_;
  std::map<std::int64_t, Eigen::Vector3d> film_forces_;  ///< the inputs' consistent nodal forces
  std::vector<bool> driven_face_;
  std::map<std::int64_t, double> prescribed_;  ///< driven node -> value along direction()
  mutable double largest_imbalance_ = 0.0;
};

}  // namespace cocopp::calculix

#pragma once
// The loads of one coupling iteration on the interface faces, as ccx cards:
// - pressure: *DLOAD "element, P<face>, p" per face (ccx integrates it; positive pushes into
//   the body, the coupler's convention too);
// - traction: ccx has no distributed traction load, so a uniform traction t on each face
//   becomes the consistent nodal forces w_i t (w_i = integral of N_i over the face, see
//   element_faces.hpp), summed over the faces, as *CLOAD. The faces are those of the actual
//   model (a 1° sector's faces span 1°), so no per-radian or per-segment factor enters. Nodes
//   with a *TRANSFORM take their *CLOAD in the local system: the forces are rotated into it.
// Every face and node is written each time (zeros too), with OP=MOD (the default): a new
// step's values replace the previous step's, and the user's own loads are left alone.
#include <Eigen/Core>
#include <filesystem>
#include <functional>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "core/data/calculix_interface_file.hpp"  // ccx_number
#include "core/data/interface.hpp"
#include "solver_wrappers/calculix/element_faces.hpp"
#include "solver_wrappers/calculix/input_deck.hpp"

namespace cocopp::calculix {

class InterfaceLoads {
 public:
  InterfaceLoads(const InputDeck& deck, std::vector<ElementFace> faces);

  const std::vector<ElementFace>& faces() const { return faces_; }
  const std::vector<FaceGeometry>& geometry() const { return geometry_; }

  /// Take the faces as their nodes have moved (deck coordinates plus `displacement`): a
  /// traction then acts on the current area, as ccx's pressure does in an NLGEOM step.
  void move_faces(const NodeDisplacements& displacement);

  /// Nodal forces (global x, y, z) of a uniform traction per face (faces x 3) and, if given,
  /// a uniform pressure per face (pushing into the body).
  std::map<std::int64_t, Eigen::Vector3d> nodal_forces(
      const RowMatrix& traction, const Eigen::VectorXd& pressure = Eigen::VectorXd()) const;
  /// Nodal forces (global) of a total force per face (faces x 3, N; `force`, mapped
  /// conservatively from the other solver's faces): each face's force spread over its nodes as
  /// a uniform traction's nodal forces are, so that the nodes take the totals exactly. On nodes
  /// with a cylindrical *TRANSFORM (a sector of a body of revolution) a face's force is
  /// axisymmetric: its part along the axis acts along the axis, its part across the axis
  /// radially at every node (inwards where it points inwards at the face's centroid), none
  /// around it (the other solver's sector, symmetric about its own middle, has none).
  std::map<std::int64_t, Eigen::Vector3d> nodal_forces_of_totals(const RowMatrix& force) const;
  /// The mean pressure (pushing into the body) per face that a total force per face gives.
  Eigen::VectorXd pressure_of_totals(const RowMatrix& force) const;

  /// A force (global x, y, z) in the node's *TRANSFORM system, as ccx takes its *CLOAD there
  /// (unchanged for a node without one).
  Eigen::Vector3d in_node_system(std::int64_t node, const Eigen::Vector3d& global) const;
  /// Whether the faces are plane elements' edges: forces in x and y only.
  bool plane() const { return plane_; }

  /// *CLOAD cards of nodal forces (global), each in its node's *TRANSFORM system if it has
  /// one; `skip(node, dof)` leaves out a direction (1-based dof).
  void write_nodal_forces(std::ostream& out, const std::map<std::int64_t, Eigen::Vector3d>& forces,
                          const std::function<bool(std::int64_t, int)>& skip = nullptr) const;

  /// Write the cards: `pressure` has one value per face (or is empty: no *DLOAD), `traction`
  /// and `force` (a total per face) one row per face (or are empty: no *CLOAD of theirs).
  void write(const std::filesystem::path& file, const Eigen::VectorXd& pressure,
             const RowMatrix& traction, const RowMatrix& force = RowMatrix()) const;

 private:
  const InputDeck& deck_;
  std::vector<ElementFace> faces_;
  std::vector<FaceGeometry> geometry_;
  bool plane_ = false;  ///< faces of plane elements: no forces out of plane
};

}  // namespace cocopp::calculix

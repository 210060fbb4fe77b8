#pragma once
// Faces of CalculiX elements: which nodes a face "S<k>" has, and its geometry from the
// isoparametric shape functions: area, centroid and the consistent nodal weights
// w_i = integral of N_i over the face, so that a uniform traction t on the face is the nodal
// forces w_i t exactly (for quadratic faces the corner weights are negative, as they must be).
// Faces of plane elements (CPE*, CPS*) are edges times the section thickness; faces of
// axisymmetric elements (CAX*, x = radius, y = axis) are edges swept around the axis: area and
// weights are for the whole ring (2 pi r), as ccx takes axisymmetric *CLOADs per 360 degrees.
#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <vector>

#include "solver_wrappers/calculix/input_deck.hpp"

namespace cocopp::calculix {

struct FaceGeometry {
  std::vector<std::int64_t> nodes;
  Eigen::VectorXd weights;  ///< integral of each node's shape function over the face
  /// Integral of each node's shape function times the outward unit normal over the face (one
  /// row per node): a pressure p (pushing into the body) is the nodal forces -p times a row.
  Eigen::MatrixXd normal_weights;
  double area = 0.0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
};

/// Node displacements by node id (nodes not listed have not moved).
using NodeDisplacements = std::map<std::int64_t, Eigen::Vector3d>;

/// Throws DeckError for element types or face numbers the wrapper does not support (the
/// message lists the supported ones). With `moved`, the face as its nodes have moved: deck
/// coordinates plus displacement.
FaceGeometry face_geometry(const InputDeck& deck, const ElementFace& face,
                           const NodeDisplacements* moved = nullptr);

}  // namespace cocopp::calculix

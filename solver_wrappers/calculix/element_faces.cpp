#include "solver_wrappers/calculix/element_faces.hpp"

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <string>

namespace cocopp::calculix {

namespace {

enum class Shape { kLine2, kLine3, kQuad4, kQuad8 };

constexpr double kPi = 3.14159265358979323846;

struct FaceTopology {
  Shape shape;
  std::vector<int> local_nodes;  ///< 1-based element node numbers, corners first
  bool plane = false;            ///< an edge of a plane element: times the thickness
  bool axisymmetric = false;     ///< an edge of a CAX element: swept around the y axis
};

// Node numbering of hexahedral faces (CalculiX manual, C3D8 and C3D20): the corner nodes of
// faces 1..6, then the mid-side nodes of C3D20.
constexpr std::array<std::array<int, 4>, 6> kHexCorners = {
    {{1, 2, 3, 4}, {5, 8, 7, 6}, {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 8, 4}, {4, 8, 5, 1}}};
constexpr std::array<std::array<int, 4>, 6> kHexMidsides = {{{9, 10, 11, 12},
                                                             {16, 15, 14, 13},
                                                             {17, 13, 18, 9},
                                                             {18, 14, 19, 10},
                                                             {19, 15, 20, 11},
                                                             {20, 16, 17, 12}}};

bool starts_with(const std::string& text, const std::string& prefix) {
  return text.rfind(prefix, 0) == 0;
}

FaceTopology topology(const std::string& type, int face, std::int64_t element) {
  const std::string where =
      "element " + std::to_string(element) + " (" + type + "), face S" + std::to_string(face);
  const bool hex8 = starts_with(type, "C3D8");
  const bool hex20 = starts_with(type, "C3D20");
  const bool axisymmetric = starts_with(type, "CAX4") || starts_with(type, "CAX8");
  const bool quad4 =
      starts_with(type, "CPE4") || starts_with(type, "CPS4") || starts_with(type, "CAX4");
  const bool quad8 =
      starts_with(type, "CPE8") || starts_with(type, "CPS8") || starts_with(type, "CAX8");
  if (hex8 || hex20) {
    if (face < 1 || face > 6) throw DeckError(where + ": hexahedra have faces S1 to S6");
    const auto& corners = kHexCorners[static_cast<std::size_t>(face - 1)];
    FaceTopology result{hex8 ? Shape::kQuad4 : Shape::kQuad8, {corners.begin(), corners.end()}};
    if (hex20) {
      const auto& mids = kHexMidsides[static_cast<std::size_t>(face - 1)];
      result.local_nodes.insert(result.local_nodes.end(), mids.begin(), mids.end());
    }
    return result;
  }
  if (quad4 || quad8) {
    if (face < 1 || face > 4) throw DeckError(where + ": quadrilaterals have faces S1 to S4");
    FaceTopology result{
        quad4 ? Shape::kLine2 : Shape::kLine3, {face, face % 4 + 1}, !axisymmetric, axisymmetric};
    if (quad8) result.local_nodes.push_back(face + 4);
    return result;
  }
  throw DeckError(where +
                  ": element type not supported for interface faces (supported: C3D8, C3D8R, "
                  "C3D8I, C3D20, C3D20R, CPE4, CPE4R, CPE8, CPE8R, CPS4, CPS4R, CPS8, CPS8R, "
                  "CAX4, CAX4R, CAX8, CAX8R)");
}

/// Shape functions of a face at natural coordinates (xi, eta); eta unused for lines.
Eigen::VectorXd shape_functions(Shape shape, double xi, double eta, Eigen::MatrixXd& derivatives) {
  // Corner and mid-side natural coordinates in the order of the face's local nodes.
  static const double quad_xi[8] = {-1, 1, 1, -1, 0, 1, 0, -1};
  static const double quad_eta[8] = {-1, -1, 1, 1, -1, 0, 1, 0};
  Eigen::VectorXd n;
  switch (shape) {
    case Shape::kLine2:
      n.resize(2);
      derivatives.resize(2, 1);
      n << (1 - xi) / 2, (1 + xi) / 2;
      derivatives << -0.5, 0.5;
      return n;
    case Shape::kLine3:  // nodes: end 1 (xi=-1), end 2 (xi=1), middle
      n.resize(3);
      derivatives.resize(3, 1);
      n << xi * (xi - 1) / 2, xi * (xi + 1) / 2, 1 - xi * xi;
      derivatives << xi - 0.5, xi + 0.5, -2 * xi;
      return n;
    case Shape::kQuad4:
      n.resize(4);
      derivatives.resize(4, 2);
      for (int i = 0; i < 4; ++i) {
        n[i] = (1 + xi * quad_xi[i]) * (1 + eta * quad_eta[i]) / 4;
        derivatives(i, 0) = quad_xi[i] * (1 + eta * quad_eta[i]) / 4;
        derivatives(i, 1) = quad_eta[i] * (1 + xi * quad_xi[i]) / 4;
      }
      return n;
    case Shape::kQuad8:
      n.resize(8);
      derivatives.resize(8, 2);
      for (int i = 0; i < 4; ++i) {
        const double a = quad_xi[i], b = quad_eta[i];
        n[i] = (1 + xi * a) * (1 + eta * b) * (xi * a + eta * b - 1) / 4;
        derivatives(i, 0) = a * (1 + eta * b) * (2 * xi * a + eta * b) / 4;
        derivatives(i, 1) = b * (1 + xi * a) * (xi * a + 2 * eta * b) / 4;
      }
      for (int i = 4; i < 8; ++i) {
        const double a = quad_xi[i], b = quad_eta[i];
        if (a == 0) {
          n[i] = (1 - xi * xi) * (1 + eta * b) / 2;
          derivatives(i, 0) = -xi * (1 + eta * b);
          derivatives(i, 1) = b * (1 - xi * xi) / 2;
        } else {
          n[i] = (1 + xi * a) * (1 - eta * eta) / 2;
          derivatives(i, 0) = a * (1 - eta * eta) / 2;
          derivatives(i, 1) = -eta * (1 + xi * a);
        }
      }
      return n;
  }
  return n;
}

}  // namespace

FaceGeometry face_geometry(const InputDeck& deck, const ElementFace& face,
                           const NodeDisplacements* moved) {
  const Element& element = deck.element(face.element);
  const FaceTopology topo = topology(element.type, face.face, face.element);
  FaceGeometry geometry;
  Eigen::MatrixXd xyz(static_cast<Eigen::Index>(topo.local_nodes.size()), 3);
  for (std::size_t i = 0; i < topo.local_nodes.size(); ++i) {
    const auto local = static_cast<std::size_t>(topo.local_nodes[i] - 1);
    if (local >= element.nodes.size())
      throw DeckError("element " + std::to_string(face.element) + " (" + element.type +
                      ") has too few nodes for face S" + std::to_string(face.face));
    geometry.nodes.push_back(element.nodes[local]);
    Eigen::Vector3d position = deck.node(element.nodes[local]);
    if (moved) {
      const auto found = moved->find(element.nodes[local]);
      if (found != moved->end()) position += found->second;
    }
    xyz.row(static_cast<Eigen::Index>(i)) = position.transpose();
  }
  // 3-point Gauss-Legendre in each direction: exact for the quadratic faces' weights on
  // straight-sided faces, and far below the .dat precision on curved ones.
  const double points[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
  const double gauss_weights[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  const bool line = topo.shape == Shape::kLine2 || topo.shape == Shape::kLine3;
  const double thickness = topo.plane ? deck.thickness(face.element) : 1.0;
  geometry.weights = Eigen::VectorXd::Zero(xyz.rows());
  geometry.normal_weights = Eigen::MatrixXd::Zero(xyz.rows(), 3);
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < (line ? 1 : 3); ++j) {
      Eigen::MatrixXd derivatives;
      const Eigen::VectorXd n =
          shape_functions(topo.shape, points[i], line ? 0.0 : points[j], derivatives);
      const Eigen::MatrixXd tangents = xyz.transpose() * derivatives;  // 3 x (1 or 2)
      // The area element's normal: for an edge of a plane or axisymmetric element the tangent
      // turned in the x-y plane; its sign is fixed below.
      const Eigen::Vector3d t0 = tangents.col(0);
      const Eigen::Vector3d area_normal =
          line ? Eigen::Vector3d(t0.y(), -t0.x(), 0.0)
               : Eigen::Vector3d(t0.cross(Eigen::Vector3d(tangents.col(1))));
      const double jacobian = area_normal.norm();
      // A CAX edge stands for the ring it sweeps (x is the radius): ccx takes the *CLOAD of
      // axisymmetric models per 360 degrees, so the weights are for the whole ring.
      const double sweep = topo.axisymmetric ? 2 * kPi * n.dot(xyz.col(0)) : thickness;
      const double w = gauss_weights[i] * (line ? 1.0 : gauss_weights[j]) * jacobian * sweep;
      geometry.weights += w * n;
      geometry.normal_weights += w * n * (area_normal / jacobian).transpose();
      first_moment += w * (xyz.transpose() * n);
    }
  }
  geometry.area = geometry.weights.sum();
  if (!(geometry.area > 0.0))
    throw DeckError("element " + std::to_string(face.element) + " face S" +
                    std::to_string(face.face) + " has no area (collapsed or repeated nodes?)");
  geometry.centroid = first_moment / geometry.area;
  // Outward: away from the element's nodes (their mean lies inside a convex element).
  Eigen::Vector3d inside = Eigen::Vector3d::Zero();
  for (const auto node : element.nodes) inside += deck.node(node);
  inside /= static_cast<double>(element.nodes.size());
  const Eigen::Vector3d mean_normal = geometry.normal_weights.colwise().sum().transpose();
  if (mean_normal.dot(geometry.centroid - inside) < 0) geometry.normal_weights *= -1.0;
  return geometry;
}

}  // namespace cocopp::calculix

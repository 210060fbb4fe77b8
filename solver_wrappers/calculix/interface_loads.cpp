#include "solver_wrappers/calculix/interface_loads.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <stdexcept>

namespace cocopp::calculix {

InterfaceLoads::InterfaceLoads(const InputDeck& deck, std::vector<ElementFace> faces)
    : deck_(deck), faces_(std::move(faces)) {
  for (const auto& face : faces_) geometry_.push_back(face_geometry(deck, face));
  // Edges of plane elements have 2 or 3 nodes; faces of solids 4 or 8.
  plane_ = !geometry_.empty() && geometry_.front().nodes.size() <= 3;
}

void InterfaceLoads::move_faces(const NodeDisplacements& displacement) {
  for (std::size_t i = 0; i < faces_.size(); ++i)
    geometry_[i] = face_geometry(deck_, faces_[i], &displacement);
}

std::map<std::int64_t, Eigen::Vector3d> InterfaceLoads::nodal_forces(
    const RowMatrix& traction, const Eigen::VectorXd& pressure) const {
  std::map<std::int64_t, Eigen::Vector3d> forces;
  for (std::size_t f = 0; f < geometry_.size(); ++f) {
    const auto& face = geometry_[f];
    const auto row = static_cast<Eigen::Index>(f);
    const Eigen::Vector3d t = traction.size() > 0 ? Eigen::Vector3d(traction.row(row).transpose())
                                                  : Eigen::Vector3d::Zero();
    const double p = pressure.size() > 0 ? pressure[row] : 0.0;
    for (std::size_t i = 0; i < face.nodes.size(); ++i) {
      const auto node = static_cast<Eigen::Index>(i);
      auto [entry, inserted] = forces.try_emplace(face.nodes[i], Eigen::Vector3d::Zero());
      (void)inserted;
      entry->second += face.weights[node] * t - p * face.normal_weights.row(node).transpose();
    }
  }
  return forces;
}

std::map<std::int64_t, Eigen::Vector3d> InterfaceLoads::nodal_forces_of_totals(
    const RowMatrix& force) const {
  std::map<std::int64_t, Eigen::Vector3d> forces;
  for (std::size_t f = 0; f < geometry_.size(); ++f) {
    const auto& face = geometry_[f];
    const Eigen::Vector3d total = force.row(static_cast<Eigen::Index>(f)).transpose();
    for (std::size_t i = 0; i < face.nodes.size(); ++i) {
      const std::int64_t node = face.nodes[i];
      // A uniform traction's share: the node's shape function integral over the face's area
      // (negative at a serendipity face's corners; the shares sum to one).
      const double share = face.weights[static_cast<Eigen::Index>(i)] / face.area;
      Eigen::Vector3d at_node = total;
      const NodalTransform* transform = deck_.transform(node);
      if (transform != nullptr && transform->type == 'C') {
        const Eigen::Vector3d axis = (transform->b - transform->a).normalized();
        const Eigen::Vector3d across = total - total.dot(axis) * axis;
        const Eigen::Vector3d outwards_at_face = transform->axes_at(face.centroid).row(0);
        const double radial = across.dot(outwards_at_face) < 0.0 ? -across.norm() : across.norm();
        const Eigen::Vector3d outwards = transform->axes_at(deck_.node(node)).row(0);
        at_node = total.dot(axis) * axis + radial * outwards;
      }
      forces.try_emplace(node, Eigen::Vector3d::Zero()).first->second += share * at_node;
    }
  }
  return forces;
}

Eigen::VectorXd InterfaceLoads::pressure_of_totals(const RowMatrix& force) const {
  Eigen::VectorXd pressure(static_cast<Eigen::Index>(geometry_.size()));
  for (std::size_t f = 0; f < geometry_.size(); ++f) {
    const auto& face = geometry_[f];
    // A uniform pressure p gives the total -p N, N the integral of the outward normal over
    // the face: the p whose total is nearest the force.
    const Eigen::Vector3d normal = face.normal_weights.colwise().sum().transpose();
    pressure[static_cast<Eigen::Index>(f)] =
        -force.row(static_cast<Eigen::Index>(f)).dot(normal.transpose()) / normal.squaredNorm();
  }
  return pressure;
}

Eigen::Vector3d InterfaceLoads::in_node_system(std::int64_t node,
                                               const Eigen::Vector3d& global) const {
  const NodalTransform* transform = deck_.transform(node);
  return transform ? Eigen::Vector3d(transform->axes_at(deck_.node(node)) * global) : global;
}

void InterfaceLoads::write_nodal_forces(std::ostream& out,
                                        const std::map<std::int64_t, Eigen::Vector3d>& forces,
                                        const std::function<bool(std::int64_t, int)>& skip) const {
  out << "*CLOAD\n";
  for (const auto& [node, global_force] : forces) {
    const Eigen::Vector3d force = in_node_system(node, global_force);
    for (int dof = 0; dof < (plane_ ? 2 : 3); ++dof)
      if (!skip || !skip(node, dof + 1))
        out << fmt::format("{}, {}, {}\n", node, dof + 1, ccx_number(force[dof]));
  }
}

void InterfaceLoads::write(const std::filesystem::path& file, const Eigen::VectorXd& pressure,
                           const RowMatrix& traction, const RowMatrix& force) const {
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write the loads file " + file.string());
  out << "** Interface loads of this coupling iteration, written by cocopp\n";
  if (pressure.size() > 0) {
    out << "*DLOAD\n";
    for (std::size_t f = 0; f < faces_.size(); ++f)
      out << fmt::format("{}, P{}, {}\n", faces_[f].element, faces_[f].face,
                         ccx_number(pressure[static_cast<Eigen::Index>(f)]));
  }
  if (traction.size() > 0) write_nodal_forces(out, nodal_forces(traction));
  if (force.size() > 0) write_nodal_forces(out, nodal_forces_of_totals(force));
  if (!out.flush()) throw std::runtime_error("cannot write the loads file " + file.string());
}

}  // namespace cocopp::calculix

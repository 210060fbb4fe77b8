#pragma once
// The interface file the calculix wrapper (solver_wrappers/calculix, mode: persistent) writes
// for cocopp-ccx (solvers/calculix) next to the deck: which of ccx's loads and nodes the
// coupler's interface is. Both sides read and write it through this one definition; standard
// library only, so that cocopp-ccx compiles it without the coupler's libraries.
//
//   amplitude ramp|step
//   initial_increment T   (each coupler time step starts with an increment of T, step time)
//   force_scale S         (what ccx makes of a *CLOAD value: 1/180 in an axisymmetric model)
//   linear 0|1            (1: no NLGEOM, no nonlinear material: one Newton iteration suffices)
//   pressure_faces N OFFSET then N lines "element face" (input pressure, *DLOAD P<face>;
//                         OFFSET 2 for plane elements, whose faces ccx numbers from 3)
//   force_nodes N DOFS    then N lines "node"           (input force, *CLOAD dofs 1..DOFS)
//   displacement_nodes N  then N lines "node"           (output displacement, ccx's dofs 1-3)
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace cocopp::calculix {

/// A number as ccx reads it from a deck or as the interface file holds it: 14 significant
/// digits in ccx's 20-character field, "0." below 1e-99 (which would need a third exponent
/// digit).
std::string ccx_number(double value);

struct InterfaceFile {
  static constexpr const char* kName = "cocopp_interface.txt";

  bool ramp = true;  ///< loads ramp over a coupling step (ccx's static default) or jump
  double initial_increment = 0.0;  ///< of each coupler time step (step time)
  double force_scale = 1.0;        ///< ccx's reading of a *CLOAD value (cloads.f)
  bool linear = false;             ///< a linear model: ccx may stop at its first Newton iteration
  std::vector<std::pair<int, int>> pressure_faces;  ///< element, face 1..6
  int face_offset = 0;  ///< ccx numbers a plane element's faces as its 3D expansion's: +2
  std::vector<int> force_nodes;
  int force_dofs = 3;
  std::vector<int> displacement_nodes;

  /// Numbers are written with ccx_number(), so that both sides hold the deck's values. Throws
  /// std::runtime_error naming the file if it cannot be written.
  void write(const std::filesystem::path& file) const;
  /// Throws std::runtime_error naming the file and what is wrong with it.
  static InterfaceFile read(const std::filesystem::path& file);
};

}  // namespace cocopp::calculix

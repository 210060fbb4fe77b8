#pragma once
// The wire drawing example's case written for a test: examples/wire_drawing/make_case.py into
// `directory` with more of its arguments (e.g. "--set die.reduction=0"), and the film meshed
// (its Allmesh: blockMesh and topoSet, which need OpenFOAM) unless `mesh_film` is false, and the
// surrogate's film too where the case has one (coupling.type iqnism).
#include <filesystem>
#include <string>

#include "tests/support/run_in.hpp"

namespace cocopp::testing {

inline const std::filesystem::path kWireDrawingExample =
    std::filesystem::path(COCOPP_TEST_SOURCE_DIR) / "examples/wire_drawing";

/// make_case.py's arguments for the paper's own coupling of the wire: axisymmetric (CAX8R),
/// taking the film's loads, a step's first update relaxed by 0.01, on the die with a sharp
/// corner these tests were measured on (the case's default is the sector driven by
/// displacement, under a die with a rounded transition).
inline const std::string kLoadDrivenWire =
    " --set mesh.wire_model=axisymmetric --set coupling.drive=load --set coupling.omega=0.01"
    " --set die.transition_length=0";

inline void write_wire_drawing_case(const std::filesystem::path& directory,
                                    const std::string& arguments = "", bool mesh_film = true) {
  run_in(directory, "/usr/bin/python3 " + (kWireDrawingExample / "make_case.py").string() +
                        " --output . " + arguments);
  if (!mesh_film) return;
  run_in(directory / "fluid", "./Allmesh");
  if (std::filesystem::exists(directory / "surrogate" / "fluid"))
    run_in(directory / "surrogate" / "fluid", "./Allmesh");
}

}  // namespace cocopp::testing

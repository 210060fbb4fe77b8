#pragma once
// Parameters of the reference tube (docs/tube-solvers.md, "The two reference examples") for
// the tube model tests.
#include "solvers/tube/tube_flow.hpp"
#include "solvers/tube/tube_ringmodel.hpp"
#include "solvers/tube/tube_structure.hpp"

namespace cocopp::tube::testing {

inline TubeGeometry reference_geometry(int cells = 100) {
  return {0.05, 0.01, cells};
}

inline TubeFlowParameters reference_flow(int cells = 100) {
  TubeFlowParameters flow;
  flow.geometry = reference_geometry(cells);
  flow.rho_f = 1000.0;
  flow.e = 3e5;
  flow.h = 1e-3;
  flow.u_ref = 1.0;
  flow.u0 = 0.0;
  flow.p_ref = 0.0;
  flow.inlet = {InletBoundary::kPressure, InletFunction::kPulse, 0.0, 1333.2, 0.003};
  flow.outlet = {OutletBoundary::kFixed, 0.0};
  flow.newtonmax = 3;
  flow.newtontol = 1e-14;
  return flow;
}

inline TubeStructureParameters reference_structure(int cells = 100) {
  TubeStructureParameters structure;
  structure.geometry = reference_geometry(cells);
  structure.rho_s = 1200.0;
  structure.e = 3e5;
  structure.h = 1e-3;
  structure.nu = 0.3;
  structure.p_ref = 0.0;
  return structure;
}

inline TubeRingmodelParameters reference_ringmodel(int cells = 100) {
  TubeRingmodelParameters rings;
  rings.geometry = reference_geometry(cells);
  rings.rho_f = 1000.0;
  rings.e = 3e5;
  rings.h = 1e-3;
  rings.p_ref = 0.0;
  return rings;
}

}  // namespace cocopp::tube::testing

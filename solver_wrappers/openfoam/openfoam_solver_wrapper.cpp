// The `openfoam` solver wrapper: an OpenFOAM case run by cocoppPimpleFoam (pimpleFoam with a
// moving mesh, stays running for the whole simulation), driven over the solver protocol.
//
// Keys (docs/solver-wrappers-openfoam.md): those of `process` (working_directory is the
// OpenFOAM case directory; the default command is [<bin>/cocoppPimpleFoam, -patches, (...)])
// plus `boundary_names`, the interface patches. check() checks the case before anything runs:
// fixed deltaT equal to the coupler's, a dynamic mesh with a motion solver, the patches in the
// mesh, the density for the loads in Pa.
#include <fmt/format.h>

#include <set>

#include "coupler/case/suggest.hpp"
#include "solver_wrappers/openfoam/openfoam_case.hpp"
#include "solver_wrappers/process/process_solver_wrapper.hpp"

namespace cocopp {

namespace {

std::vector<std::string> read_boundary_names(const Settings& settings) {
  const auto names = settings.required<std::vector<std::string>>("boundary_names");
  if (names.empty())
    settings.fail("boundary_names", "give the interface patches of the OpenFOAM mesh, e.g. [wall]");
  std::set<std::string> seen;
  for (const auto& name : names)
    if (!seen.insert(name).second)
      settings.fail("boundary_names", "patch '" + name + "' is listed twice");
  return names;
}

DefaultCommand pimple_foam_command(const std::vector<std::string>& boundary_names) {
  // OpenFOAM's list syntax for the word list option: -patches '(wall top)'.
  return {builtin_solver_directory() / "cocoppPimpleFoam",
          "",
          {"-patches", "(" + join(boundary_names, " ") + ")"},
          // All of OpenFOAM's environment that Debian's build needs (its etc/ files); its
          // libraries read it while they load.
          {{"WM_PROJECT_DIR", "/usr/share/openfoam"}}};
}

class OpenFoamSolverWrapper : public ProcessSolverWrapper {
 public:
  OpenFoamSolverWrapper(const Settings& settings, const RunSettings& run)
      : OpenFoamSolverWrapper(settings, run, read_boundary_names(settings)) {}

  void check() const override {
    ProcessSolverWrapper::check();
    openfoam::CaseCheck{working_directory(), boundary_names_, delta_t_, "solver '" + name() + "': "}
        .run();
  }

 private:
  OpenFoamSolverWrapper(const Settings& settings, const RunSettings& run,
                        std::vector<std::string> boundary_names)
      : ProcessSolverWrapper(settings, run, pimple_foam_command(boundary_names)),
        boundary_names_(std::move(boundary_names)),
        delta_t_(run.delta_t) {}

  std::vector<std::string> boundary_names_;
  double delta_t_;
};

}  // namespace

COCOPP_REGISTER(SolverWrapperRegistry, "openfoam", OpenFoamSolverWrapper)

}  // namespace cocopp

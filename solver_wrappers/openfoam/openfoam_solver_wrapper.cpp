// The `openfoam` solver wrapper: an OpenFOAM case run by cocoppPimpleFoam (pimpleFoam with a
// moving mesh, stays running for the whole simulation), driven over the solver protocol.
//
// Keys (docs/solver-wrappers-openfoam.md): those of `process` (working_directory is the
// OpenFOAM case directory; the default command is [<bin>/cocoppPimpleFoam, -patches, (...)])
// plus `boundary_names`, the interface patches, `gap_patch` (the interface faces then also
// output their gap to this patch, the points their wall displacement), and `cores`: more than 1
// decomposes the case (decomposePar) and runs the application under mpirun. check() checks the case
// before anything runs: fixed deltaT equal to the coupler's, a dynamic mesh with a motion solver,
// the patches in the mesh, the density for the loads in Pa, the decomposition.
// `sensitivity_probe` (a film): the film measures its own sensitivity to its wall each step by
// finite differences, for the calculix wrapper's `film_stiffness: probed`.
#include <fmt/format.h>

#include <set>

#include "core/case/suggest.hpp"
#include "core/protocol/transport.hpp"
#include "solver_wrappers/openfoam/openfoam_case.hpp"
#include "solver_wrappers/process/child_process.hpp"
#include "solver_wrappers/process/process_solver_wrapper.hpp"
#include "solver_wrappers/solver_error.hpp"

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

/// The `sensitivity_probe` mapping as cocoppPimpleFoam's COCOPP_SENSITIVITY_PROBE
/// ('STEP MOVE FILE warm|cold hat=K', the file relative to the case); empty without the key.
std::vector<std::pair<std::string, std::string>> sensitivity_probe(const Settings& settings,
                                                                   int cores) {
  if (!settings.has("sensitivity_probe")) return {};
  const Settings probe = settings.child("sensitivity_probe");
  if (settings.get<std::string>("gap_patch", "").empty())
    settings.fail("sensitivity_probe",
                  "the probe measures a film: give its gap_patch too (the wall it faces)");
  if (cores != 1)
    settings.fail("sensitivity_probe",
                  fmt::format("the film probes itself in a serial run only: remove the key or "
                              "set cores: 1 (it is {})",
                              cores));
  const std::string file = probe.required<std::string>("file");
  if (file.empty() || file.find_first_of(" \t\n") != std::string::npos)
    probe.fail("file", "give a file name without spaces, relative to the OpenFOAM case");
  std::string step = probe.get<std::string>("step", "every");
  if (step != "every") step = std::to_string(probe.get_int_in_range("step", 1, 1));
  const double move = probe.get_in_range("move", 1e-8, Range::positive());
  const std::string start = probe.get_choice("start", "warm", {"warm", "cold"});
  const int hat = probe.get_int_in_range("hat", 1, 1, 1000);
  return {{"COCOPP_SENSITIVITY_PROBE",
           fmt::format("{} {} {} {} hat={}", step, move, file, start, hat)}};
}

DefaultCommand pimple_foam_command(const std::vector<std::string>& boundary_names, int cores,
                                   const std::string& gap_patch, bool tcp) {
  const std::string application = (builtin_solver_directory() / "cocoppPimpleFoam").string();
  // OpenFOAM's list syntax for the word list option: -patches '(wall top)'.
  std::vector<std::string> patches = {"-patches", "(" + join(boundary_names, " ") + ")"};
  if (!gap_patch.empty()) patches.insert(patches.end(), {"-gapPatch", gap_patch});
  // All of OpenFOAM's environment that Debian's build needs (its etc/ files); its libraries
  // read it while they load.
  const std::vector<std::pair<std::string, std::string>> environment = {
      {"WM_PROJECT_DIR", "/usr/share/openfoam"}};
  if (cores == 1) return {application, "", patches, environment, {}};
  std::vector<std::string> arguments = {"--allow-run-as-root",
                                        "--oversubscribe",
                                        "-np",
                                        std::to_string(cores),
                                        "-x",
                                        "WM_PROJECT_DIR",
                                        "-x",
                                        protocol::kTransportVariable,
                                        "-x",
                                        protocol::kChannelVariable};
  // The TCP channel's secret goes to the ranks as the rest of the channel does: by mpirun's
  // environment, never on a command line.
  if (tcp) arguments.insert(arguments.end(), {"-x", protocol::kTokenVariable});
  arguments.insert(arguments.end(), {application, "-parallel"});
  arguments.insert(arguments.end(), patches.begin(), patches.end());
  return {"mpirun", "", arguments, environment, {}};
}

class OpenFoamSolverWrapper : public ProcessSolverWrapper {
 public:
  OpenFoamSolverWrapper(const Settings& settings, const RunSettings& run)
      : OpenFoamSolverWrapper(settings, run, read_boundary_names(settings),
                              settings.get_int_in_range("cores", 1, 1),
                              settings.get<std::string>("gap_patch", "")) {
    set_case_environment(sensitivity_probe(settings, cores_));
  }

  void check() const override {
    ProcessSolverWrapper::check();
    // With substeps, the fluid's own time step is the coupler's divided by them.
    openfoam::CaseCheck{working_directory(), boundary_names_, delta_t_ / substeps(),
                        "solver '" + name() + "': ", cores_}
        .run();
  }

  void initialize() override {
    // A fresh parallel run decomposes the case; a restart uses the processor directories of
    // the run it continues.
    if (cores_ > 1 && timestep_start_ == 0) decompose();
    ProcessSolverWrapper::initialize();
  }

 private:
  OpenFoamSolverWrapper(const Settings& settings, const RunSettings& run,
                        std::vector<std::string> boundary_names, int cores,
                        const std::string& gap_patch)
      : ProcessSolverWrapper(
            settings, run,
            pimple_foam_command(boundary_names, cores, gap_patch,
                                settings.get<std::string>("transport", "") == "tcp")),
        boundary_names_(std::move(boundary_names)),
        cores_(cores),
        delta_t_(run.delta_t),
        timestep_start_(run.timestep_start) {}

  void decompose() {
    check();
    const auto log = working_directory() / "log.decomposePar";
    ChildOptions options;
    options.command = {"decomposePar", "-force"};
    options.working_directory = working_directory();
    options.environment = {{"WM_PROJECT_DIR", "/usr/share/openfoam"}};
    options.log_file = log;
    try {
      ChildProcess decompose_par(options);
      if (decompose_par.wait_for_exit(kDecomposeTimeoutSeconds) && decompose_par.exit_code() == 0)
        return;
      const std::string what = decompose_par.running() ? fmt::format("did not finish within {} s",
                                                                     kDecomposeTimeoutSeconds)
                                                       : decompose_par.describe_exit();
      decompose_par.stop(2.0);
      throw SolverError(
          name(),
          fmt::format("solver '{}': decomposePar {} in {}; last lines of {}:\n{}", name(), what,
                      working_directory().string(), log.string(), read_last_lines(log, 20)));
    } catch (const SolverError&) {
      throw;
    } catch (const std::exception& e) {
      throw SolverError(name(), "solver '" + name() + "': cannot run decomposePar: " + e.what());
    }
  }

  static constexpr double kDecomposeTimeoutSeconds = 600.0;
  std::vector<std::string> boundary_names_;
  int cores_;
  double delta_t_;
  int timestep_start_;
};

}  // namespace

COCOPP_REGISTER(SolverWrapperRegistry, "openfoam", OpenFoamSolverWrapper)

}  // namespace cocopp

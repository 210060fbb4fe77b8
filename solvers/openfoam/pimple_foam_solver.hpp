#pragma once
// PimpleFoamSolver: OpenFOAM's pimpleFoam (transient incompressible flow, PIMPLE, moving mesh)
// as a cocopp solver that stays running for the whole simulation.
//
// Per time step the time advances once (initialize_step). Per coupling iteration (solve) the
// absolute displacement of the interface patch points (relative to the initial mesh,
// points0) becomes the fixedValue of `pointDisplacement` on those patches, the mesh moves with
// the case's motion solver and the PIMPLE loop runs. Every solve of a step starts from the
// state at the start of the step: the solution fields (every registered field that OpenFOAM
// writes) and the mesh points are put back first, so repeated iterations do not drift and the
// first one is exactly pimpleFoam's time step. Committing a step (finalize_step) writes the
// fields when controlDict says so; save_restart (the coupler saves its state) writes them now,
// and a run restarted after step n starts from the time directory of n * delta_t.
//
// Interface, per patch P of `-patches`: model part `P_points` (the patch points, ids = mesh
// point labels; input `displacement`) and `P_faces` (the face centres, ids = mesh face labels;
// output `pressure` and `traction`), both sorted by label of the undecomposed mesh, so that a
// parallel run has the interface of the serial one. In parallel every rank runs this class;
// the master gathers the loads (see ParallelSolver in main_cocopp_pimple_foam.cpp). Loads are in
// Pa: the kinematic pressure and stress times `rho` from constant/transportProperties. `traction`
// is the viscous force per area of the fluid on the wall, rho * (n & devReff) with n the outward
// normal of the fluid domain (= -rho * OpenFOAM's wallShearStress).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "CorrectPhi.H"
#include "dynamicFvMesh.H"
#include "fvCFD.H"
#include "fvOptions.H"
#include "pimpleControl.H"
#include "singlePhaseTransportModel.H"
#include "solvers/openfoam/patch_numbering.hpp"
#include "solvers/sdk/solver_sdk.hpp"
#include "turbulentTransportModel.H"

namespace cocopp::openfoam {

class StepStartState;
class WindowStartState;
class FlowFields;

/// The initial residual of each solve of a field recorded in a solverPerformanceDict entry,
/// the largest over the directions the geometry has: the normal component of a wedge (or an
/// empty direction) is solved as noise around zero, and its normalised residual says nothing.
/// OpenFOAM's own residual control counts it, so that a wedge never meets a velocity
/// tolerance (1e-3 on the wire drawing film where the other components are converged).
Foam::scalarList initial_residuals(const Foam::fvMesh& mesh, const Foam::entry& performance);

/// pimpleControl that can abandon a PIMPLE loop part way (an input rejected after the mesh
/// motion), so that the next solve starts again from the first outer corrector, and whose
/// residual control judges only the directions the geometry has (initial_residuals).
class RestartablePimpleControl : public Foam::pimpleControl {
 public:
  using Foam::pimpleControl::pimpleControl;
  void abandon_loop() {
    corr_ = 0;
    corrPISO_ = 0;
    converged_ = false;
    mesh_.data::remove("finalIteration");
  }
  /// Solver-coupling convergence needs residual controls and a second outer corrector.
  bool has_residual_controls() const { return !residualControl_.empty() && nCorrPIMPLE() > 1; }
  /// The residualControl entry that applies to `field` (-1: none), and its tolerance.
  Foam::label control_index(const Foam::word& field) const { return applyToField(field); }
  Foam::scalar tolerance(Foam::label control) const { return residualControl_[control].absTol; }

 protected:
  /// pimpleControl's check (absolute tolerance, or relative to the second corrector's
  /// residual), on initial_residuals().
  bool criteriaSatisfied() override;
};

/// OpenFOAM's Time that a restart can start at another time than controlDict's startTime, as
/// if the run had been started there: function objects then write their files under that time
/// (postProcessing/<name>/<time>/), not over the first run's.
class CoupledTime : public Foam::Time {
 public:
  using Foam::Time::Time;
  void start_at(const Foam::instant& time, Foam::label index) {
    setTime(time, index);
    startTime_ = time.value();
    startTimeIndex_ = index;
  }
  /// With substeps the solver decides when to write (the windows' ends): Time's own flag,
  /// raised by the time index, would write function objects' state at a substep.
  void clear_write_flag() { writeTime_ = false; }
  /// The step before this one as infinitely long: OpenFOAM's backward scheme is then Euler,
  /// as it makes its first step (by the time index, which substeps keep counting on).
  void as_first_step() { deltaT0_ = Foam::GREAT; }
};

/// COCOPP_SENSITIVITY_PROBE='STEP MOVE FILE [cold|warm] [hat=K]': at step STEP's (or every
/// step's: 'every') first coupling iteration, solve the step again per hoop line of the wall
/// moved radially by MOVE (m) and write the faces' force changes to FILE
/// (sensitivity_probe.cpp); warm: each probe starts from the step's solution; hat=K: every K-th
/// line, the lines between moved linearly less. Step 0: off.
struct SensitivityProbe {
  int step = 0;
  double move = 0.0;
  std::string file;
  bool warm = false;  ///< each probe starts from the step's solution, not the step's start
  int hat = 1;        ///< every hat-th line probed, its neighbours moved by a hat function
  static SensitivityProbe from_environment();
};

class PimpleFoamSolver : public sdk::Solver {
 public:
  /// `gap_patch`: if not empty, the interface faces also output their gap to this patch and
  /// the force on each face (`force`: pressure and shear on its current area, N), and the
  /// interface points their displacement (`wall_displacement`).
  PimpleFoamSolver(Foam::argList& args, const Foam::wordList& patch_names,
                   const Foam::word& gap_patch = Foam::word());
  ~PimpleFoamSolver() override;

  sdk::InterfaceDescription initialize(const sdk::RunInfo& run) override;
  void initialize_step(std::int32_t step, double time) override;
  std::vector<double> solve(const std::vector<double>& input) override;
  void finalize_step() override;
  void finalize() override;
  /// A restart starts from the time directory of its step (start_at_coupler_step), which
  /// save_restart writes whatever controlDict's writeControl says.
  bool can_restart() const override { return true; }
  void save_restart(std::int32_t step) override;
  /// From now on the flow of every coupling iteration starts from the previous iterate's (on
  /// the step's start mesh), and the solve reports whether the first outer corrector's initial
  /// residuals were below residualControl's tolerances. Needs PIMPLE { nOuterCorrectors > 1;
  /// residualControl {...} } in fvSolution.
  void start_reporting_convergence() override;
  bool converged_at_first_iteration() const override { return converged_at_first_iteration_; }
  /// Substeps: the time, the fields with their old times, the mesh with its old volumes and
  /// flux go back to the window's start at each coupling iteration (WindowStartState); the
  /// fields are written, and the function objects run, at the windows' ends only.
  bool can_substep() const override { return true; }
  void save_state() override;
  void restore_state() override;
  void finalize_substep() override;

 private:
  /// What pimpleFoam creates before its time loop (createTime, the mesh, createFields, ...).
  void create_case(const sdk::RunInfo& run);
  void start_at_coupler_step(const sdk::RunInfo& run);
  void find_patches();
  void check_run(const sdk::RunInfo& run) const;
  const Foam::pointField& initial_points() const;
  Foam::pointVectorField& point_displacement();
  /// The state at the start of the step, for every solve of the step.
  void store_step_start();
  void restore_step_start();
  void clear_residual_record();
  /// After the first outer corrector: the initial residual of every solve of a field with a
  /// residualControl entry was below its tolerance.
  bool first_corrector_met_residual_controls() const;
  void set_interface_displacement(const std::vector<double>& input);
  /// One PIMPLE time step without advancing time: the body of pimpleFoam's time loop.
  void solve_pimple();
  /// Rejects the input (sdk::InputRejected) if the mesh motion left a cell with no or negative
  /// volume.
  void check_cells_not_inverted() const;
  /// Rejects the input (sdk::InputRejected) once the outer loop diverges on it.
  void check_not_diverging(label corrector) const;
  std::vector<double> loads() const;
  /// Substeps go back with the old times of Euler and backward only.
  void check_time_scheme_for_substeps() const;
  /// Whether controlDict's writeControl asks for a write in the window that ends now.
  bool window_holds_write_time() const;
  /// Per face of interface patch `id`: the distance from its centre to the gap patch (on every
  /// rank's faces of it).
  Foam::scalarField gaps(Foam::label id) const;
  sdk::InterfaceDescription interface_description() const;
  /// The film's force per face against each hoop line's radial move (SensitivityProbe).
  void probe_sensitivity(const std::vector<double>& input, const std::vector<double>& output);
  std::size_t input_size() const;

  Foam::argList& args_;
  Foam::wordList patch_names_;
  Foam::labelList patch_ids_;
  Foam::word gap_patch_name_;
  Foam::label gap_patch_id_ = -1;
  std::vector<PatchNumbering> numbering_;  ///< per patch: the coupler's order
  double rho_ = 0.0;

  Foam::autoPtr<CoupledTime> run_time_;
  Foam::autoPtr<Foam::dynamicFvMesh> mesh_;
  Foam::autoPtr<RestartablePimpleControl> pimple_;
  Foam::autoPtr<Foam::volScalarField> p_;
  Foam::autoPtr<Foam::volVectorField> U_;
  Foam::autoPtr<Foam::surfaceScalarField> phi_;
  Foam::autoPtr<Foam::surfaceVectorField> Uf_;
  Foam::autoPtr<Foam::singlePhaseTransportModel> laminar_transport_;
  Foam::autoPtr<Foam::incompressible::turbulenceModel> turbulence_;
  Foam::autoPtr<Foam::IOMRFZoneList> MRF_;
  Foam::fv::options* fv_options_ = nullptr;
  Foam::label p_ref_cell_ = 0;
  Foam::scalar p_ref_value_ = 0.0;
  Foam::scalar cumulative_continuity_error_ = 0.0;
  bool correct_phi_ = false;
  bool check_mesh_courant_number_ = false;
  bool move_mesh_outer_correctors_ = false;

  std::unique_ptr<StepStartState> step_start_;
  std::unique_ptr<FlowFields> previous_iterate_;    ///< with solver-coupling convergence only
  std::unique_ptr<WindowStartState> window_start_;  ///< with substeps only
  int window_iteration_ = 0;                        ///< of the window, from 0
  int window_substep_ = 0;                          ///< in this iteration of the window
  bool mesh_moved_in_window_ = false;               ///< since the window's start
  int iteration_ = 0;
  int step_ = 0;
  SensitivityProbe probe_ = SensitivityProbe::from_environment();
  bool stepped_ = false;
  bool warm_start_ = false;      ///< coupling iterations continue from the previous iterate
  bool restore_fields_ = false;  ///< even so: the last solve was abandoned part way
  bool converged_at_first_iteration_ = false;
};

}  // namespace cocopp::openfoam

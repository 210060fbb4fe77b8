#include "solvers/openfoam/pimple_foam_solver.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "displacementMotionSolver.H"
#include "dynamicMotionSolverFvMesh.H"
#include "fixedValuePointPatchFields.H"
#include "points0MotionSolver.H"
#include "solvers/openfoam/step_start_state.hpp"

namespace cocopp::openfoam {

using namespace Foam;

namespace {

/// Run `action`, turning OpenFOAM's errors (thrown, see main) into std::runtime_error with
/// OpenFOAM's message, which the SDK sends to the coupler. The log gets the full error.
template <class Action>
auto reporting_foam_errors(Action&& action) {
  try {
    return action();
  } catch (const Foam::error& e) {
    Perr << nl << e << endl;
    throw std::runtime_error(std::string(e.message()));
  }
}

/// decomposePar's map from a processor mesh to the undecomposed one.
labelIOList read_addressing(const fvMesh& mesh, const word& name) {
  return labelIOList(IOobject(name, mesh.facesInstance(), polyMesh::meshSubDir, mesh,
                              IOobject::MUST_READ, IOobject::NO_WRITE, false));
}

std::string patch_list(const wordList& names) {
  std::string text;
  for (const word& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

}  // namespace

PimpleFoamSolver::PimpleFoamSolver(argList& args, const wordList& patch_names,
                                   const word& gap_patch)
    : args_(args),
      patch_names_(patch_names),
      gap_patch_name_(gap_patch),
      step_start_(std::make_unique<StepStartState>()) {}

PimpleFoamSolver::~PimpleFoamSolver() = default;

sdk::InterfaceDescription PimpleFoamSolver::initialize(const sdk::RunInfo& run) {
  return reporting_foam_errors([&] {
    create_case(run);
    find_patches();
    check_run(run);
    return interface_description();
  });
}

void PimpleFoamSolver::create_case(const sdk::RunInfo& run) {
  run_time_.reset(new CoupledTime(Time::controlDictName, args_));
  Time& runTime = *run_time_;
  start_at_coupler_step(run);
  Info << "Create mesh for time = " << runTime.timeName() << nl << endl;
  mesh_ = dynamicFvMesh::New(args_, runTime);
  dynamicFvMesh& mesh = *mesh_;
  if (!isA<dynamicMotionSolverFvMesh>(mesh))
    FatalErrorInFunction << "cocoppPimpleFoam moves the mesh with a motion solver: set "
                         << "dynamicFvMesh dynamicMotionSolverFvMesh in "
                         << runTime.constant() / "dynamicMeshDict" << exit(FatalError);
  const motionSolver& motion = refCast<const dynamicMotionSolverFvMesh>(mesh).motion();
  if (!isA<displacementMotionSolver>(motion))
    FatalErrorInFunction << "cocoppPimpleFoam needs a displacement motion solver (e.g. "
                         << "displacementLaplacian) in " << runTime.constant() / "dynamicMeshDict"
                         << ", not " << motion.type() << exit(FatalError);

  pimple_.reset(new RestartablePimpleControl(mesh));
  const dictionary& pimple_dict = pimple_->dict();
  correct_phi_ = pimple_dict.lookupOrDefault("correctPhi", mesh.dynamic());
  check_mesh_courant_number_ = pimple_dict.lookupOrDefault("checkMeshCourantNo", false);
  move_mesh_outer_correctors_ = pimple_dict.lookupOrDefault("moveMeshOuterCorrectors", false);
  if (runTime.controlDict().lookupOrDefault("adjustTimeStep", false))
    FatalIOErrorInFunction(runTime.controlDict())
        << "adjustTimeStep is on: the coupler sets the time step; remove it or set it to no"
        << exit(FatalIOError);

  // pimpleFoam's createFields.H.
  Info << "Reading field p\n" << endl;
  p_.reset(new volScalarField(
      IOobject("p", runTime.timeName(), mesh, IOobject::MUST_READ, IOobject::AUTO_WRITE), mesh));
  Info << "Reading field U\n" << endl;
  U_.reset(new volVectorField(
      IOobject("U", runTime.timeName(), mesh, IOobject::MUST_READ, IOobject::AUTO_WRITE), mesh));
  phi_.reset(new surfaceScalarField(
      IOobject("phi", runTime.timeName(), mesh, IOobject::READ_IF_PRESENT, IOobject::AUTO_WRITE),
      fvc::flux(*U_)));
  setRefCell(*p_, pimple_dict, p_ref_cell_, p_ref_value_);
  mesh.setFluxRequired(p_->name());
  laminar_transport_.reset(new singlePhaseTransportModel(*U_, *phi_));
  turbulence_ = incompressible::turbulenceModel::New(*U_, *phi_, *laminar_transport_);
  MRF_.reset(new IOMRFZoneList(mesh));
  fv_options_ = &fv::options::New(mesh);
  // createUfIfPresent.H
  Uf_.reset(new surfaceVectorField(
      IOobject("Uf", runTime.timeName(), mesh, IOobject::READ_IF_PRESENT, IOobject::AUTO_WRITE),
      fvc::interpolate(*U_)));
  turbulence_->validate();

  // Loads in Pa: pimpleFoam works with kinematic pressure and stress.
  if (!laminar_transport_->found("rho"))
    FatalIOErrorInFunction(*laminar_transport_)
        << "the fluid density rho (kg/m^3) is missing: cocoppPimpleFoam returns loads in Pa, "
        << "the kinematic pressure and stress times rho" << exit(FatalIOError);
  rho_ = dimensionedScalar("rho", dimDensity, *laminar_transport_).value();
}

void PimpleFoamSolver::start_at_coupler_step(const sdk::RunInfo& run) {
  // The coupler's start step picks the time directory (a restart), whatever startFrom says.
  CoupledTime& runTime = *run_time_;
  const scalar start = run.timestep_start * run.delta_t;
  const instant closest = runTime.findClosestTime(start);
  if (std::abs(closest.value() - start) > 1e-6 * run.delta_t)
    FatalErrorInFunction << "the coupler starts at step " << run.timestep_start << " (time "
                         << start << ") but the case has no time directory for it; its times: "
                         << runTime.times() << exit(FatalError);
  if (closest.value() != runTime.value() || run.timestep_start != runTime.timeIndex()) {
    Info << "Starting at time " << closest.name() << ", the coupler's step " << run.timestep_start
         << nl << endl;
    runTime.start_at(closest, run.timestep_start);
  }
}

void PimpleFoamSolver::find_patches() {
  const polyBoundaryMesh& boundary = mesh_->boundaryMesh();
  if (patch_names_.empty())
    FatalErrorInFunction << "no interface patches: give them with -patches '(name ...)'"
                         << exit(FatalError);
  // The undecomposed mesh's labels of this rank's points and faces.
  const labelList point_labels = Pstream::parRun()
                                     ? labelList(read_addressing(*mesh_, "pointProcAddressing"))
                                     : identity(mesh_->nPoints());
  labelList face_labels = Pstream::parRun()
                              ? labelList(read_addressing(*mesh_, "faceProcAddressing"))
                              : identity(mesh_->nFaces());
  if (Pstream::parRun())
    for (label& face : face_labels) face = mag(face) - 1;  // stored +-(label + 1), - if flipped
  patch_ids_.setSize(patch_names_.size());
  forAll(patch_names_, i) {
    patch_ids_[i] = boundary.findPatchID(patch_names_[i]);
    if (patch_ids_[i] < 0)
      FatalErrorInFunction << "interface patch " << patch_names_[i] << " is not in "
                           << mesh_->boundaryMesh().objectPath()
                           << "; the patches are: " << boundary.names() << exit(FatalError);
    if (!isA<fixedValuePointPatchVectorField>(point_displacement().boundaryField()[patch_ids_[i]]))
      FatalErrorInFunction << "pointDisplacement on interface patch " << patch_names_[i]
                           << " is of type "
                           << point_displacement().boundaryField()[patch_ids_[i]].type()
                           << ": it must be fixedValue (cocoppPimpleFoam sets its values) in "
                           << run_time_->timePath() / "pointDisplacement" << exit(FatalError);
    numbering_.emplace_back(boundary[patch_ids_[i]], point_labels, face_labels);
  }
  if (gap_patch_name_.empty()) return;
  gap_patch_id_ = boundary.findPatchID(gap_patch_name_);
  if (gap_patch_id_ < 0)
    FatalErrorInFunction << "the gap patch " << gap_patch_name_ << " (-gapPatch) is not in "
                         << mesh_->boundaryMesh().objectPath()
                         << "; the patches are: " << boundary.names() << exit(FatalError);
}

void PimpleFoamSolver::check_run(const sdk::RunInfo& run) const {
  const Time& runTime = *run_time_;
  const scalar delta_t = runTime.deltaTValue();
  if (std::abs(delta_t - run.delta_t) > 1e-12 * std::abs(run.delta_t))
    FatalIOErrorInFunction(runTime.controlDict())
        << "deltaT " << delta_t << " in controlDict differs from the coupler's delta_t "
        << run.delta_t << exit(FatalIOError);
}

const pointField& PimpleFoamSolver::initial_points() const {
  const auto& mesh = refCast<const dynamicMotionSolverFvMesh>(*mesh_);
  return refCast<const points0MotionSolver>(mesh.motion()).points0();
}

pointVectorField& PimpleFoamSolver::point_displacement() {
  auto& mesh = refCast<const dynamicMotionSolverFvMesh>(*mesh_);
  // motion() is const only: the displacement is the motion solver's input we set.
  return const_cast<displacementMotionSolver&>(
             refCast<const displacementMotionSolver>(mesh.motion()))
      .pointDisplacement();
}

sdk::InterfaceDescription PimpleFoamSolver::interface_description() const {
  sdk::InterfaceDescription description;
  const pointField& points0 = initial_points();
  forAll(patch_ids_, i) {
    const polyPatch& patch = mesh_->boundaryMesh()[patch_ids_[i]];
    const PatchNumbering& numbering = numbering_[i];
    // Coordinates of the initial mesh (a restart may start moved); face centres likewise.
    const auto point_coordinates =
        numbering.gather_points(flatten(pointField(points0, patch.meshPoints())), 3);
    pointField centres(patch.size());
    forAll(patch, face_i) centres[face_i] = patch[face_i].centre(points0);
    const auto face_coordinates = numbering.gather_faces(flatten(centres), 3);
    const auto ids = [](const std::vector<label>& labels) {
      return std::vector<std::int64_t>(labels.begin(), labels.end());
    };
    // With a gap patch the points also report where the wall stands (their displacement: what
    // a structure driven under the film is driven to), and the faces their gap.
    description.model_parts.push_back({patch_names_[i] + "_points",
                                       ids(numbering.point_ids()),
                                       point_coordinates,
                                       {"displacement"},
                                       gap_patch_id_ < 0
                                           ? std::vector<std::string>{}
                                           : std::vector<std::string>{"wall_displacement"}});
    description.model_parts.push_back(
        {patch_names_[i] + "_faces",
         ids(numbering.face_ids()),
         face_coordinates,
         {},
         gap_patch_id_ < 0 ? std::vector<std::string>{"pressure", "traction"}
                           : std::vector<std::string>{"pressure", "traction", "gap", "force"}});
  }
  description.initial_output = loads();
  return description;
}

std::size_t PimpleFoamSolver::input_size() const {
  std::size_t size = 0;
  for (const PatchNumbering& numbering : numbering_) size += 3 * numbering.point_ids().size();
  return size;
}

void PimpleFoamSolver::initialize_step(std::int32_t step, double time) {
  reporting_foam_errors([&] {
    Time& runTime = *run_time_;
    // run() also runs the function objects of the last step, as pimpleFoam; with substeps
    // only on a window's converged start, not on the substeps of its coupling iterations.
    ++window_substep_;
    const bool committed = !window_start_ || (window_iteration_ == 0 && window_substep_ == 1);
    if (!(committed ? runTime.run()
                    : runTime.value() < runTime.endTime().value() - 0.5 * runTime.deltaTValue()))
      FatalIOErrorInFunction(runTime.controlDict())
          << "the coupler asks for step " << step << " (time " << time << ") but endTime is "
          << runTime.endTime().value() << ": raise endTime in controlDict" << exit(FatalIOError);
    ++runTime;
    if (window_start_) {
      run_time_->clear_write_flag();
      // The run's first step by the time, whatever the time index says.
      if (std::lround(runTime.value() / runTime.deltaTValue()) < 2) run_time_->as_first_step();
    }
    stepped_ = true;
    if (std::abs(runTime.value() - time) > 1e-6 * runTime.deltaTValue())
      FatalErrorInFunction << "time " << runTime.timeName() << " after advancing, but the "
                           << "coupler's step " << step << " is at time " << time
                           << exit(FatalError);
    Info << "Time = " << runTime.timeName() << nl << endl;
    const dictionary& pimple_dict = pimple_->dict();
    correct_phi_ = pimple_dict.lookupOrDefault("correctPhi", correct_phi_);
    check_mesh_courant_number_ =
        pimple_dict.lookupOrDefault("checkMeshCourantNo", check_mesh_courant_number_);
    move_mesh_outer_correctors_ =
        pimple_dict.lookupOrDefault("moveMeshOuterCorrectors", move_mesh_outer_correctors_);
    step_start_->store(*mesh_);
    iteration_ = 0;
    step_ = step;
  });
}

std::vector<double> PimpleFoamSolver::solve(const std::vector<double>& input) {
  return reporting_foam_errors([&] {
    if (input.size() != input_size())
      FatalErrorInFunction << "solve was given " << label(input.size())
                           << " displacement values; the interface patches "
                           << patch_list(patch_names_) << " have " << label(input_size())
                           << exit(FatalError);
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    auto restored = start;
    if (++iteration_ > 1) {
      if (warm_start_ && !restore_fields_) {
        // The flow goes on from the previous iterate, on the step's start geometry (see
        // FlowFields); PIMPLE's residual record starts afresh with the restore, so that the
        // first corrector's residuals say how far that iterate is from this input's solution.
        previous_iterate_->store(*mesh_);
        restore_step_start();
        previous_iterate_->restore(*mesh_);
        Info << "Coupling iteration " << iteration_ << ": solving time " << run_time_->timeName()
             << " again from the previous iterate's flow" << nl << endl;
      } else {
        restore_step_start();
        Info << "Coupling iteration " << iteration_ << ": solving time " << run_time_->timeName()
             << " again from the start of the step" << nl << endl;
      }
      restored = Clock::now();
    }
    restore_fields_ = false;
    converged_at_first_iteration_ = false;
    set_interface_displacement(input);
    mesh_moved_in_window_ = true;  // in the first outer corrector
    const auto pimple_start = Clock::now();
    try {
      solve_pimple();
    } catch (const sdk::InputRejected&) {
      pimple_->abandon_loop();  // the next solve restores the step's start (iteration_ > 1)
      restore_fields_ = true;   // also with a warm start: the fields are half solved
      throw;
    }
    const auto pimple_end = Clock::now();
    std::vector<double> output = loads();
    if ((probe_.step == step_ || probe_.step < 0) && iteration_ == 1 && !window_start_)
      probe_sensitivity(input, output);
    // What the coupling adds inside the solver (restoring the step's start, the interface
    // data) against the PIMPLE solve itself: read by bench/openfoam_overhead.
    const std::chrono::duration<double> pimple = pimple_end - pimple_start;
    const std::chrono::duration<double> restore = restored - start;
    const std::chrono::duration<double> interface =
        (pimple_start - restored) + (Clock::now() - pimple_end);
    Info << "cocopp coupling iteration " << iteration_ << ": PIMPLE " << pimple.count()
         << " s, restore " << restore.count() << " s, interface " << interface.count() << " s" << nl
         << endl;
    return output;
  });
}

void PimpleFoamSolver::restore_step_start() {
  step_start_->restore(*mesh_);
  clear_residual_record();
}

// PIMPLE's residual controls look at the first solve of the time step.
void PimpleFoamSolver::clear_residual_record() {
  const_cast<dictionary&>(mesh_->solverPerformanceDict()).clear();
}

scalarList initial_residuals(const fvMesh& mesh, const entry& performance) {
  const word& field = performance.keyword();
  if (mesh.foundObject<volScalarField>(field)) {
    const List<SolverPerformance<scalar>> solves(performance.stream());
    scalarList residuals(solves.size());
    forAll(solves, i) residuals[i] = solves[i].initialResidual();
    return residuals;
  }
  if (mesh.foundObject<volVectorField>(field)) {
    const List<SolverPerformance<vector>> solves(performance.stream());
    const Vector<label>& directions = mesh.geometricD();
    scalarList residuals(solves.size(), 0.0);
    forAll(solves, i) for (direction d = 0; d < vector::nComponents; ++d) if (directions[d] == 1)
        residuals[i] = max(residuals[i], solves[i].initialResidual()[d]);
    return residuals;
  }
  FatalErrorInFunction << "residualControl names " << field
                       << ", which is neither a scalar nor a vector field: cocoppPimpleFoam "
                          "controls only those"
                       << exit(FatalError);
  return {};
}

bool RestartablePimpleControl::criteriaSatisfied() {
  // As pimpleControl: nothing to judge before the second corrector or in the final one.
  if (corr_ == 1 || residualControl_.empty() || finalIter()) return false;
  const bool store_initial = storeInitialResiduals();
  bool achieved = true;
  bool checked = false;
  for (const entry& performance : mesh_.solverPerformanceDict()) {
    const label control = applyToField(performance.keyword());
    if (control < 0) continue;
    const scalarList residuals = initial_residuals(mesh_, performance);
    if (residuals.empty()) continue;
    checked = true;
    fieldData& data = residualControl_[control];
    bool relative = false;
    if (store_initial)
      data.initialResidual = residuals.first();
    else
      relative = residuals.last() / (data.initialResidual + ROOTVSMALL) < data.relTol;
    achieved = achieved && (residuals.last() < data.absTol || relative);
  }
  return checked && achieved;
}

bool PimpleFoamSolver::first_corrector_met_residual_controls() const {
  bool checked = false;
  for (const entry& performance : mesh_->solverPerformanceDict()) {
    const label control = pimple_->control_index(performance.keyword());
    if (control < 0) continue;
    checked = true;
    if (!(max(initial_residuals(*mesh_, performance)) < pimple_->tolerance(control))) return false;
  }
  return checked;
}

void PimpleFoamSolver::start_reporting_convergence() {
  reporting_foam_errors([&] {
    if (!pimple_->has_residual_controls())
      FatalErrorInFunction
          << "solver-coupling convergence needs PIMPLE's residual controls: "
          << mesh_->time().system() / "fvSolution"
          << " has nOuterCorrectors " << pimple_->nCorrPIMPLE()
          << " and no residualControl. Give PIMPLE nOuterCorrectors > 1 and, per field, "
             "residualControl { p { tolerance 1e-6; relTol 0; } U { tolerance 1e-6; relTol 0; "
             "} }: cocoppPimpleFoam then reports whether the first outer corrector's residuals "
             "were below them"
          << exit(FatalError);
  });
  warm_start_ = true;
  previous_iterate_ = std::make_unique<FlowFields>();
  Info << "cocopp: solver-coupling convergence reported; the flow of every coupling iteration "
          "starts from the previous iterate's"
       << nl << endl;
}

void PimpleFoamSolver::set_interface_displacement(const std::vector<double>& input) {
  pointVectorField& displacement = point_displacement();
  std::size_t offset = 0;
  forAll(patch_ids_, i) {
    const labelList& positions = numbering_[i].local_point_positions();
    vectorField values(positions.size());
    forAll(values, point) for (direction d = 0; d < 3; ++d) values[point][d] =
        input[offset + 3 * positions[point] + d];
    refCast<fixedValuePointPatchVectorField>(displacement.boundaryFieldRef()[patch_ids_[i]]) ==
        values;
    offset += 3 * numbering_[i].point_ids().size();
  }
}

void PimpleFoamSolver::solve_pimple() {
  // pimpleFoam's names, so that its equation files (UEqn.H, pEqn.H, correctPhi.H) read as
  // they are.
  Time& runTime = *run_time_;
  dynamicFvMesh& mesh = *mesh_;
  pimpleControl& pimple = *pimple_;
  volScalarField& p = *p_;
  volVectorField& U = *U_;
  surfaceScalarField& phi = *phi_;
  autoPtr<surfaceVectorField>& Uf = Uf_;
  singlePhaseTransportModel& laminarTransport = *laminar_transport_;
  autoPtr<incompressible::turbulenceModel>& turbulence = turbulence_;
  IOMRFZoneList& MRF = *MRF_;
  fv::options& fvOptions = *fv_options_;
  const label pRefCell = p_ref_cell_;
  const scalar pRefValue = p_ref_value_;
  scalar& cumulativeContErr = cumulative_continuity_error_;
  using Foam::solve;  // not this class's solve()

  while (pimple.loop()) {
    if (warm_start_ && pimple.corr() == 2)
      converged_at_first_iteration_ = first_corrector_met_residual_controls();
    if (pimple.firstIter() || move_mesh_outer_correctors_) {
      mesh.controlledUpdate();  // solves the motion with the interface displacement
      check_cells_not_inverted();
      if (mesh.changing()) {
        MRF.update();
        if (correct_phi_) {
          // The absolute flux from the mapped surface velocity
          phi = mesh.Sf() & Uf();
#include "correctPhi.H"
          // relative to the mesh motion
          fvc::makeRelative(phi, U);
        }
        if (check_mesh_courant_number_) {
#include "meshCourantNo.H"
        }
      }
    }
#include "UEqn.H"
    while (pimple.correct()) {
#include "pEqn.H"
      check_not_diverging(pimple.corr());
    }
    if (pimple.turbCorr()) {
      laminarTransport.correct();
      turbulence->correct();
    }
  }
  (void)runTime;  // used by some of the included files only
}

void PimpleFoamSolver::check_not_diverging(label corrector) const {
  // The volume the absolute fluxes fail to balance in a time step, relative to the cells'
  // volume (pimpleFoam's "sum local" continuity error): about 1e-11 in a converged film step,
  // and it grows without bound where the outer loop diverges on an input it cannot take (a
  // coupling iterate that squeezes a thin film too far). Reject such an input before the
  // floating-point overflow kills the solver, so that the coupler can step back.
  const scalar error =
      run_time_->deltaTValue() *
      mag(fvc::div(fvc::absolute(*phi_, *U_)))().weightedAverage(mesh_->V()).value();
  const scalar fastest = gMax(mag(U_->primitiveField())());
  if (error < 1 && std::isfinite(error) && std::isfinite(fastest)) return;
  OStringStream message;
  message << "the flow diverged in coupling iteration " << iteration_ << " at time "
          << run_time_->timeName() << ": after PIMPLE outer corrector " << corrector
          << " the continuity error is " << error << " of the cells' volume per time step "
          << "(fastest velocity " << fastest
          << "). What to change: a smaller time step, a wall that moves less per time step, or "
             "(for a coupling iterate far off) a smaller first relaxation (coupled_solver.omega)";
  throw sdk::InputRejected(message.str());
}

void PimpleFoamSolver::check_cells_not_inverted() const {
  // A boundary that moves across the cell layers next to it (a die closing onto the wire
  // faster than the film can carry) turns cells inside out: their volume is zero or negative.
  // The flow would then be solved on it and fail later, or worse, not at all.
  const scalarField& volumes = mesh_->V();
  label inverted = 0, worst = -1;
  forAll(volumes, cell) {
    if (volumes[cell] > 0) continue;
    ++inverted;
    if (worst < 0 || volumes[cell] < volumes[worst]) worst = cell;
  }
  if (returnReduce(inverted, sumOp<label>()) == 0) return;
  const vector centre = worst >= 0 ? mesh_->C()[worst] : vector::zero;
  // The input may be at fault (a coupling iterate far off): reject it, so that the coupler
  // can step back; if the prescribed motion alone inverts cells, the retries fail alike.
  OStringStream message;
  message << "the mesh motion of coupling iteration " << iteration_ << " at time "
          << run_time_->timeName() << " turned " << inverted
          << " cell(s) inside out (the worst, cell " << worst << " at " << centre << ", has volume "
          << (worst >= 0 ? volumes[worst] : 0.0)
          << "): a boundary moved across the cells next to it. What to change: a wall that "
             "closes more slowly (a smaller prescribed motion per time step), a smaller time "
             "step, or more room between the walls";
  throw sdk::InputRejected(message.str());
}

std::vector<double> PimpleFoamSolver::loads() const {
  std::vector<double> values;  // gathered on the master
  const tmp<volSymmTensorField> deviatoric_stress = turbulence_->devReff();  // kinematic
  // The output layout: per patch, with a gap patch the points' wall displacement (model part
  // P_points); then (P_faces) the pressures, the tractions and with a gap patch the gaps and
  // the forces.
  forAll(patch_ids_, i) {
    const label id = patch_ids_[i];
    if (gap_patch_id_ >= 0) {
      const labelList& points = mesh_->boundaryMesh()[id].meshPoints();
      const pointField wall(pointField(mesh_->points(), points) -
                            pointField(initial_points(), points));
      const auto part = numbering_[i].gather_points(flatten(wall), 3);
      values.insert(values.end(), part.begin(), part.end());
    }
    const scalarField pressure(rho_ * p_->boundaryField()[id]);
    const vectorField normals(mesh_->boundary()[id].nf());
    const vectorField traction(rho_ * (normals & deviatoric_stress().boundaryField()[id]));
    for (const auto& part : {numbering_[i].gather_faces(pressure, 1),
                             numbering_[i].gather_faces(flatten(traction), 3)})
      values.insert(values.end(), part.begin(), part.end());
    if (gap_patch_id_ < 0) continue;
    // A film also gives the force each face puts on the wall as it stands now (N, pressure
    // and shear on the face's area, what OpenFOAM's forces function object sums): a
    // structure under it takes these totals, so that none of the film's load is lost where
    // the two meshes differ (a conservative mapping).
    const vectorField force(pressure * mesh_->boundary()[id].Sf() +
                            traction * mesh_->boundary()[id].magSf());
    for (const auto& part :
         {numbering_[i].gather_faces(gaps(id), 1), numbering_[i].gather_faces(flatten(force), 3)})
      values.insert(values.end(), part.begin(), part.end());
  }
  return values;
}

scalarField PimpleFoamSolver::gaps(label id) const {
  // The gap patch's faces from every rank (a film's wall has a few hundred), then the
  // distance from each interface face centre to the nearest of them.
  const polyPatch& gap_patch = mesh_->boundaryMesh()[gap_patch_id_];
  List<List<pointField>> faces(Pstream::nProcs());
  faces[Pstream::myProcNo()].setSize(gap_patch.size());
  forAll(gap_patch, f) faces[Pstream::myProcNo()][f] = gap_patch[f].points(mesh_->points());
  Pstream::gatherList(faces);
  Pstream::scatterList(faces);
  const vectorField centres(mesh_->boundaryMesh()[id].faceCentres());
  scalarField result(centres.size(), GREAT);
  for (const auto& rank : faces)
    for (const auto& points : rank) {
      const face polygon(identity(points.size()));
      forAll(centres, i) result[i] =
          min(result[i], polygon.nearestPoint(centres[i], points).distance());
    }
  return result;
}

void PimpleFoamSolver::finalize_step() {
  reporting_foam_errors([&] {
    if (!window_start_)
      run_time_->write();  // when controlDict's writeControl says so
    else if (window_holds_write_time())
      run_time_->writeNow();
    run_time_->printExecutionTime(Info);
  });
}

void PimpleFoamSolver::save_state() {
  reporting_foam_errors([&] {
    if (!window_start_) {
      check_time_scheme_for_substeps();
      window_start_ = std::make_unique<WindowStartState>();
    }
    window_start_->store(*mesh_);
    window_iteration_ = 0;
    window_substep_ = 0;
    mesh_moved_in_window_ = false;
  });
}

void PimpleFoamSolver::check_time_scheme_for_substeps() const {
  // Euler keeps one old time, backward two and its first step by the time index (see
  // initialize_step); CrankNicolson keeps its own old-time fields by the index, which goes on
  // counting through a window's coupling iterations: not restored.
  const ITstream& stream = mesh_->ddtScheme("default");
  const word scheme = stream.size() && stream[0].isWord() ? stream[0].wordToken() : word();
  if (scheme != "Euler" && scheme != "backward")
    FatalErrorInFunction << "substeps need ddtSchemes { default Euler; } or backward in "
                         << mesh_->time().system() / "fvSchemes"
                         << ", not " << (scheme.empty() ? word("none") : scheme)
                         << ": cocoppPimpleFoam goes back to a window's start with the old "
                            "times these keep"
                         << exit(FatalError);
}

void PimpleFoamSolver::restore_state() {
  reporting_foam_errors([&] {
    window_start_->restore(*mesh_, *run_time_, mesh_moved_in_window_);
    clear_residual_record();
    pimple_->abandon_loop();  // after a rejected input, the loop may stand part way
    restore_fields_ = false;
    ++window_iteration_;
    window_substep_ = 0;
    mesh_moved_in_window_ = false;
    Info << "Coupling iteration " << window_iteration_ + 1 << " of the window from time "
         << run_time_->timeName() << ": its substeps again from its start" << nl << endl;
  });
}

void PimpleFoamSolver::finalize_substep() {
  // The window has not converged: nothing is written; the next substep goes on from here.
  reporting_foam_errors([&] { run_time_->printExecutionTime(Info); });
}

bool PimpleFoamSolver::window_holds_write_time() const {
  // Time's own write flags go by the time index, which keeps counting through a window's
  // coupling iterations, or are raised once, in its first: decide from the times instead.
  const Time& runTime = *run_time_;
  const dictionary& control = runTime.controlDict();
  const word write_control = control.get<word>("writeControl");
  const scalar interval = control.get<scalar>("writeInterval");
  const scalar delta_t = runTime.deltaTValue(), from = window_start_->time(), to = runTime.value();
  if (write_control == "timeStep") {
    const auto steps = [&](scalar time) { return std::lround(time / delta_t); };
    const long every = std::max(1L, std::lround(interval));
    return steps(to) / every > steps(from) / every;
  }
  if (write_control == "runTime" || write_control == "adjustableRunTime") {
    const scalar start = runTime.startTime().value();
    const auto writes = [&](scalar time) {
      return static_cast<long>(std::floor((time - start + 0.5 * delta_t) / interval));
    };
    return writes(to) > writes(from);
  }
  return runTime.writeTime();
}

void PimpleFoamSolver::save_restart(std::int32_t step) {
  reporting_foam_errors([&] {
    // By the time: with substeps the time index keeps counting through the coupling
    // iterations of a window (WindowStartState).
    const scalar step_time = step * run_time_->deltaTValue();
    if (std::abs(run_time_->value() - step_time) > 1e-6 * run_time_->deltaTValue())
      FatalErrorInFunction << "the coupler asks for the restart data of step " << step << " (time "
                           << step_time << ") but the solver is at time " << run_time_->timeName()
                           << exit(FatalError);
    run_time_->writeNow();  // the fields and the moved mesh, for a restart from this time
  });
}

void PimpleFoamSolver::finalize() {
  reporting_foam_errors([&] {
    // pimpleFoam's last runTime.run(): the function objects of the last step, then their end.
    if (stepped_ && run_time_->run()) run_time_->functionObjects().end();
    Info << "End\n" << endl;
  });
}

}  // namespace cocopp::openfoam

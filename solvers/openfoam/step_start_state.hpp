#pragma once
// The state at the start of a time step that every coupling iteration of cocoppPimpleFoam
// starts from: the mesh points and a copy of every field OpenFOAM writes, restored exactly.
// With substeps, the state at the start of a coupling time window: the same with the fields'
// old times, the old cell volumes, the mesh flux and the time.
#include <algorithm>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

#include "fvMesh.H"
#include "pointFields.H"
#include "surfaceFields.H"
#include "volFields.H"

namespace cocopp::openfoam {

using Foam::fvMesh;
using Foam::HashTable;
using Foam::IOobject;
using Foam::label;
using Foam::objectRegistry;
using Foam::pointField;
using Foam::pointVectorField;
using Foam::scalar;
using Foam::scalarField;
using Foam::surfaceScalarField;
using Foam::surfaceVectorField;
using Foam::Time;
using Foam::volScalarField;
using Foam::volSymmTensorField;
using Foam::volVectorField;
using Foam::word;

/// Copies of the fields of one type that OpenFOAM writes (the solution: U, p, phi, Uf,
/// turbulence fields, cellDisplacement, pointDisplacement, ...), by name, without their
/// old-time fields.
template <class Field>
class FieldCopies {
 public:
  /// All of them but those named in `skip`.
  void store(const objectRegistry& registry, const std::vector<word>& skip = {}) {
    copies_.clear();
    const HashTable<const Field*> fields = registry.lookupClass<Field>();
    for (const word& name : fields.sortedToc()) {
      const Field* field = fields[name];
      if (field->writeOpt() != IOobject::AUTO_WRITE) continue;
      if (std::find(skip.begin(), skip.end(), name) != skip.end()) continue;
      if (is_old_time(name, fields)) continue;
      IOobject io(field->name() + "_cocoppCopy", field->instance(), field->db(), IOobject::NO_READ,
                  IOobject::NO_WRITE, false);
      copies_.emplace_back(field->name(), std::make_unique<Field>(io, *field));
    }
  }
  void restore(const objectRegistry& registry) const {
    for (const auto& [name, copy] : copies_)
      const_cast<Field&>(registry.lookupObject<Field>(name)) == *copy;
  }

 private:
  /// U_0 (and U_0_0) of a field U: OpenFOAM writes a field's old times once it keeps two of
  /// them (second-order schemes such as `backward`), and shifts them itself, lazily, at the
  /// first change of the field in a time step, after the step's start was copied here. Put
  /// back by a restore, they would be the previous step's old times: a coupling iteration
  /// then differentiates in time against U one step too old (measured on the Turek-Hron
  /// channel: 15 times pimpleFoam's pressure on the flag after 20 steps).
  static bool is_old_time(const word& name, const HashTable<const Field*>& fields) {
    const std::string suffix = "_0";
    return name.size() > suffix.size() &&
           name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0 &&
           fields.found(name.substr(0, name.size() - suffix.size()));
  }

  std::vector<std::pair<word, std::unique_ptr<Field>>> copies_;
};

/// One `Per<Field>` for each type of field that a state keeps, all called alike.
template <template <class> class Per>
struct EveryFieldType {
  template <class Action>
  void each(Action&& action) {
    each_of(*this, action);
  }
  template <class Action>
  void each(Action&& action) const {
    each_of(*this, action);
  }
  Per<volScalarField> vol_scalars;
  Per<volVectorField> vol_vectors;
  Per<volSymmTensorField> vol_symm_tensors;
  Per<surfaceScalarField> surface_scalars;
  Per<surfaceVectorField> surface_vectors;
  Per<pointVectorField> point_vectors;

 private:
  template <class Self, class Action>
  static void each_of(Self& self, Action& action) {
    action(self.vol_scalars);
    action(self.vol_vectors);
    action(self.vol_symm_tensors);
    action(self.surface_scalars);
    action(self.surface_vectors);
    action(self.point_vectors);
  }
};

/// The state at the start of a time step that every coupling iteration starts from.
class StepStartState {
 public:
  void store(const fvMesh& mesh) {
    points_ = mesh.points();
    fields_.each([&](auto& copies) { copies.store(mesh); });
  }
  void restore(fvMesh& mesh) const {
    // Back to the mesh of the step's start: the motion solver and the discretisation depend
    // on the current geometry. The old-time points and volumes of the step stay as they are.
    mesh.movePoints(points_);
    fields_.each([&](const auto& copies) { copies.restore(mesh); });
  }

 private:
  pointField points_;
  EveryFieldType<FieldCopies> fields_;
};

/// The flow fields of a coupling iterate, without the mesh and the motion solver's fields.
/// With solver-coupling convergence the next iterate starts from them, but on the step's start
/// geometry: the mesh motion then stays a function of the input alone (the Laplacian motion
/// solver depends on the current geometry), while the flow starts from the previous iterate.
class FlowFields {
 public:
  void store(const fvMesh& mesh) {
    vol_scalars_.store(mesh);
    vol_vectors_.store(mesh, kMotionFields);
    vol_symm_tensors_.store(mesh);
    surface_scalars_.store(mesh);
    surface_vectors_.store(mesh);
  }
  void restore(const fvMesh& mesh) const {
    vol_scalars_.restore(mesh);
    vol_vectors_.restore(mesh);
    vol_symm_tensors_.restore(mesh);
    surface_scalars_.restore(mesh);
    surface_vectors_.restore(mesh);
  }

 private:
  /// The cell fields of OpenFOAM's displacement and velocity motion solvers.
  inline static const std::vector<word> kMotionFields = {"cellDisplacement", "cellMotionU"};
  FieldCopies<volScalarField> vol_scalars_;
  FieldCopies<volVectorField> vol_vectors_;
  FieldCopies<volSymmTensorField> vol_symm_tensors_;
  FieldCopies<surfaceScalarField> surface_scalars_;
  FieldCopies<surfaceVectorField> surface_vectors_;
};

/// One field's values and those of its old times (U, U_0, U_0_0 as far as OpenFOAM keeps
/// them), internal and on every patch (a point field's patches hold no values of their own
/// but a fixedValue's, which the solver sets at each solve).
template <class Field>
class FieldHistory {
 public:
  explicit FieldHistory(const Field& field) {
    const Field* level = &field;
    for (label i = 0;; ++i) {
      Level copy{level->primitiveField(), {}};
      if constexpr (kPatchesHoldValues) {
        copy.patches.setSize(level->boundaryField().size());
        forAll(copy.patches, patch) copy.patches[patch] = level->boundaryField()[patch];
      }
      levels_.push_back(std::move(copy));
      if (i == field.nOldTimes()) break;
      level = &level->oldTime();
    }
  }
  /// Puts the values back without OpenFOAM shifting old times (primitiveFieldRef(false)), and
  /// marks the field current at `time_index`: it shifts them at the next time index.
  ///
  /// A level that did not exist at the window's start (U_0 and U_0_0 in the first window,
  /// made by the time scheme in its first iteration) cannot be removed again: it gets the
  /// oldest stored level's values, a history at rest before the window. (A second-order
  /// scheme such as backward then starts the first window with that history in its second
  /// and later iterations, where OpenFOAM's first step is Euler: docs/coupling.md.)
  void restore(Field& field, label time_index) const {
    Field* level = &field;
    for (label i = 0; i <= field.nOldTimes(); ++i) {
      if (i > 0) level = &const_cast<Field&>(level->oldTime());
      const Level& values = levels_[std::min<std::size_t>(i, levels_.size() - 1)];
      level->primitiveFieldRef(false) = values.internal;
      if constexpr (kPatchesHoldValues) {
        auto& boundary = level->boundaryFieldRef(false);
        forAll(boundary, patch) boundary[patch] == values.patches[patch];
      }
      level->timeIndex() = time_index;
    }
  }

 private:
  using Values = typename Field::Internal::FieldType;
  static constexpr bool kPatchesHoldValues = std::is_base_of_v<Values, typename Field::Patch>;
  struct Level {
    Values internal;
    Foam::List<Values> patches;
  };
  std::vector<Level> levels_;
};

/// FieldHistory of every field of one type that OpenFOAM writes, by name.
template <class Field>
class FieldHistories {
 public:
  void store(const objectRegistry& registry) {
    histories_.clear();
    const HashTable<const Field*> fields = registry.lookupClass<Field>();
    for (const word& name : fields.sortedToc()) {
      const Field* field = fields[name];
      if (field->writeOpt() != IOobject::AUTO_WRITE) continue;
      histories_.emplace_back(name, FieldHistory<Field>(*field));
    }
  }
  void restore(const objectRegistry& registry, label time_index) const {
    for (const auto& [name, history] : histories_)
      history.restore(const_cast<Field&>(registry.lookupObject<Field>(name)), time_index);
  }

 private:
  std::vector<std::pair<word, FieldHistory<Field>>> histories_;
};

/// Whether `get` runs without an OpenFOAM error (errors are thrown: see main).
template <class Get>
bool available(Get&& get) {
  try {
    get();
    return true;
  } catch (const Foam::error&) {
    return false;
  }
}

/// The state at the start of a coupling time window of substeps, which every coupling
/// iteration of the window starts from. The time goes back to the window's start, but its
/// index goes on: OpenFOAM keeps a field's, the cells' and the mesh flux's old times by the
/// time index (a new index shifts them), so the state is put back as current at today's index,
/// and the next substep's new index shifts it into the old times as at the window's start.
class WindowStartState {
 public:
  void store(const fvMesh& mesh) {
    time_ = mesh.time().value();
    points_ = mesh.points();
    // The old volumes and the mesh flux exist once the mesh has moved, or were read at a
    // restart: their accessors fail otherwise.
    old_volumes_.reset(available([&] { mesh.V0(); }) ? new scalarField(mesh.V0()) : nullptr);
    mesh_flux_.reset(available([&] { mesh.phi(); })
                         ? new FieldHistory<surfaceScalarField>(mesh.phi())
                         : nullptr);
    fields_.each([&](auto& histories) { histories.store(mesh); });
  }
  /// `mesh_has_moved`: since the window's start (else it stands as it was then).
  void restore(fvMesh& mesh, Time& time, bool mesh_has_moved) const {
    const label index = time.timeIndex();
    time.setTime(time_, index);
    if (mesh_has_moved) {
      // At the same index: the mesh's old points and volumes stay as they are.
      mesh.movePoints(points_);
      // No old volumes at the window's start (the first window): as if the mesh had stood
      // still before it; likewise no mesh flux.
      static_cast<scalarField&>(mesh.setV0()) = old_volumes_ ? *old_volumes_ : mesh.V().field();
      if (mesh_flux_)
        mesh_flux_->restore(mesh.setPhi(), index);
      else
        mesh.setPhi() == Foam::dimensionedScalar(Foam::dimVolume / Foam::dimTime, Foam::Zero);
    }
    fields_.each([&](const auto& histories) { histories.restore(mesh, index); });
  }
  scalar time() const { return time_; }

 private:
  scalar time_ = 0;
  pointField points_;
  std::unique_ptr<scalarField> old_volumes_;
  std::unique_ptr<FieldHistory<surfaceScalarField>> mesh_flux_;
  EveryFieldType<FieldHistories> fields_;
};

}  // namespace cocopp::openfoam

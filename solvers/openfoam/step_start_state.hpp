#pragma once
// The state at the start of a time step that every coupling iteration of cocoppPimpleFoam
// starts from: the mesh points and a copy of every field OpenFOAM writes, restored exactly.
#include <algorithm>
#include <memory>
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
using Foam::objectRegistry;
using Foam::pointField;
using Foam::pointVectorField;
using Foam::surfaceScalarField;
using Foam::surfaceVectorField;
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

/// The state at the start of a time step that every coupling iteration starts from.
class StepStartState {
 public:
  void store(const fvMesh& mesh) {
    points_ = mesh.points();
    vol_scalars_.store(mesh);
    vol_vectors_.store(mesh);
    vol_symm_tensors_.store(mesh);
    surface_scalars_.store(mesh);
    surface_vectors_.store(mesh);
    point_vectors_.store(mesh);
  }
  void restore(fvMesh& mesh) const {
    // Back to the mesh of the step's start: the motion solver and the discretisation depend
    // on the current geometry. The old-time points and volumes of the step stay as they are.
    mesh.movePoints(points_);
    vol_scalars_.restore(mesh);
    vol_vectors_.restore(mesh);
    vol_symm_tensors_.restore(mesh);
    surface_scalars_.restore(mesh);
    surface_vectors_.restore(mesh);
    point_vectors_.restore(mesh);
  }

 private:
  pointField points_;
  FieldCopies<volScalarField> vol_scalars_;
  FieldCopies<volVectorField> vol_vectors_;
  FieldCopies<volSymmTensorField> vol_symm_tensors_;
  FieldCopies<surfaceScalarField> surface_scalars_;
  FieldCopies<surfaceVectorField> surface_vectors_;
  FieldCopies<pointVectorField> point_vectors_;
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

}  // namespace cocopp::openfoam

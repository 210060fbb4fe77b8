// The boundary condition `cocoppSlidingWallVelocity`: the velocity of a fluid wall that slides
// along the fixed fluid grid, as the surface of a drawn wire does (the kinematic condition of a
// sliding FSI interface). On the patch the fluid velocity is
//   U = (Uw - n (n . Uw)) + n Un,
// the tangential part of the wall's material velocity Uw (`wallVelocity`, a Function1 of time)
// plus the normal velocity of the moving mesh, Un = mesh flux / face area, so that no fluid
// crosses the moving wall. OpenFOAM's movingWallVelocity keeps only the mesh motion (the grid
// does not move axially with the wire), fixedValue only Uw. In a case (0/U):
//
//   wire { type cocoppSlidingWallVelocity; wallVelocity constant (0 0 1); value uniform (0 0 0); }
//
// Compiled into cocoppPimpleFoam and selected by name like any OpenFOAM boundary condition.
#include "Function1.H"
#include "addToRunTimeSelectionTable.H"
#include "fixedValueFvPatchFields.H"
#include "fvcMeshPhi.H"
#include "surfaceFields.H"
#include "volFields.H"

namespace Foam {

class cocoppSlidingWallVelocityFvPatchVectorField : public fixedValueFvPatchVectorField {
 public:
  TypeName("cocoppSlidingWallVelocity");

  cocoppSlidingWallVelocityFvPatchVectorField(const fvPatch& p,
                                              const DimensionedField<vector, volMesh>& iF)
      : fixedValueFvPatchVectorField(p, iF) {}

  cocoppSlidingWallVelocityFvPatchVectorField(const fvPatch& p,
                                              const DimensionedField<vector, volMesh>& iF,
                                              const dictionary& dict)
      : fixedValueFvPatchVectorField(p, iF, dict, false),
        wall_velocity_(Function1<vector>::New("wallVelocity", dict)) {
    if (dict.found("value"))
      fvPatchVectorField::operator=(vectorField("value", dict, p.size()));
    else
      fvPatchVectorField::operator=(tangential_wall_velocity());
  }

  cocoppSlidingWallVelocityFvPatchVectorField(
      const cocoppSlidingWallVelocityFvPatchVectorField& other, const fvPatch& p,
      const DimensionedField<vector, volMesh>& iF, const fvPatchFieldMapper& mapper)
      : fixedValueFvPatchVectorField(other, p, iF, mapper),
        wall_velocity_(other.wall_velocity_.clone()) {}

  cocoppSlidingWallVelocityFvPatchVectorField(
      const cocoppSlidingWallVelocityFvPatchVectorField& other)
      : fixedValueFvPatchVectorField(other), wall_velocity_(other.wall_velocity_.clone()) {}

  cocoppSlidingWallVelocityFvPatchVectorField(
      const cocoppSlidingWallVelocityFvPatchVectorField& other,
      const DimensionedField<vector, volMesh>& iF)
      : fixedValueFvPatchVectorField(other, iF), wall_velocity_(other.wall_velocity_.clone()) {}

  tmp<fvPatchVectorField> clone() const override {
    return tmp<fvPatchVectorField>(new cocoppSlidingWallVelocityFvPatchVectorField(*this));
  }
  tmp<fvPatchVectorField> clone(const DimensionedField<vector, volMesh>& iF) const override {
    return tmp<fvPatchVectorField>(new cocoppSlidingWallVelocityFvPatchVectorField(*this, iF));
  }

  void updateCoeffs() override {
    if (updated()) return;
    vectorField value(tangential_wall_velocity());
    const fvMesh& mesh = internalField().mesh();
    if (mesh.moving()) {
      // The normal velocity of the moving faces: their swept volume per time and area (the
      // mesh flux), as movingWallVelocity takes it, so the wall stays impermeable.
      const volVectorField& U = static_cast<const volVectorField&>(internalField());
      const scalarField mesh_flux(patch().patchField<surfaceScalarField, scalar>(fvc::meshPhi(U)));
      value += patch().nf() * mesh_flux / (patch().magSf() + VSMALL);
    }
    vectorField::operator=(value);
    fixedValueFvPatchVectorField::updateCoeffs();
  }

  void write(Ostream& os) const override {
    fvPatchVectorField::write(os);
    wall_velocity_->writeData(os);
    writeEntry("value", os);
  }

 private:
  /// Uw - n (n . Uw) on every face, at the current time.
  tmp<vectorField> tangential_wall_velocity() const {
    const vector wall = wall_velocity_->value(db().time().timeOutputValue());
    const vectorField n(patch().nf());
    return tmp<vectorField>(new vectorField(wall - n * (n & wall)));
  }

  autoPtr<Function1<vector>> wall_velocity_;
};

makePatchTypeField(fvPatchVectorField, cocoppSlidingWallVelocityFvPatchVectorField);

}  // namespace Foam

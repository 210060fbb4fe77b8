// The point boundary condition `cocoppRadialDisplacement`: a patch that moves radially about an
// axis by a prescribed schedule, as the die of a wire-drawing case closes onto the wire. Every
// point of the patch moves by d(t) (`radialDisplacement`, a Function1 of time; negative moves
// towards the axis) along its own radial direction, the normal from the axis through the point,
// so that on an axisymmetric wedge the points of both wedge planes move in their own planes.
// The value is the displacement from the initial mesh (points0), as displacement motion solvers
// take it. In a case (0/pointDisplacement):
//
//   die
//   {
//       type               cocoppRadialDisplacement;
//       origin             (0 0 0);
//       axis               (0 0 1);
//       radialDisplacement table ((0 0) (0.001 0) (0.008 -3.85e-05));
//       value              uniform (0 0 0);
//   }
//
// Compiled into cocoppPimpleFoam and selected by name like any OpenFOAM boundary condition.
#include "Function1.H"
#include "Time.H"
#include "addToRunTimeSelectionTable.H"
#include "fixedValuePointPatchFields.H"
#include "pointPatchFields.H"
#include "polyMesh.H"

namespace Foam {

class cocoppRadialDisplacementPointPatchVectorField : public fixedValuePointPatchField<vector> {
 public:
  TypeName("cocoppRadialDisplacement");

  cocoppRadialDisplacementPointPatchVectorField(const pointPatch& p,
                                                const DimensionedField<vector, pointMesh>& iF)
      : fixedValuePointPatchField<vector>(p, iF), origin_(Zero), axis_(0, 0, 1) {}

  cocoppRadialDisplacementPointPatchVectorField(const pointPatch& p,
                                                const DimensionedField<vector, pointMesh>& iF,
                                                const dictionary& dict)
      : fixedValuePointPatchField<vector>(p, iF, dict, false),
        origin_(dict.get<vector>("origin")),
        axis_(dict.get<vector>("axis")),
        displacement_(Function1<scalar>::New("radialDisplacement", dict)) {
    if (mag(axis_) < VSMALL)
      FatalIOErrorInFunction(dict) << "axis must not be zero" << exit(FatalIOError);
    axis_ /= mag(axis_);
    directions_ = radial_directions(dict);
    // The base has read `value` where there is one (a restart's time directory has the last
    // one); a second read of a nonuniform list fails, its token taken by the first.
    if (!dict.found("value")) updateCoeffs();
  }

  cocoppRadialDisplacementPointPatchVectorField(
      const cocoppRadialDisplacementPointPatchVectorField& other, const pointPatch& p,
      const DimensionedField<vector, pointMesh>& iF, const pointPatchFieldMapper& mapper)
      : fixedValuePointPatchField<vector>(other, p, iF, mapper),
        origin_(other.origin_),
        axis_(other.axis_),
        displacement_(other.displacement_.clone()),
        directions_(other.directions_, mapper) {}

  cocoppRadialDisplacementPointPatchVectorField(
      const cocoppRadialDisplacementPointPatchVectorField& other,
      const DimensionedField<vector, pointMesh>& iF)
      : fixedValuePointPatchField<vector>(other, iF),
        origin_(other.origin_),
        axis_(other.axis_),
        displacement_(other.displacement_.clone()),
        directions_(other.directions_) {}

  autoPtr<pointPatchField<vector>> clone() const override {
    return autoPtr<pointPatchField<vector>>(
        new cocoppRadialDisplacementPointPatchVectorField(*this, this->internalField()));
  }
  autoPtr<pointPatchField<vector>> clone(
      const DimensionedField<vector, pointMesh>& iF) const override {
    return autoPtr<pointPatchField<vector>>(
        new cocoppRadialDisplacementPointPatchVectorField(*this, iF));
  }

  void updateCoeffs() override {
    if (this->updated()) return;
    const scalar d = displacement_->value(this->db().time().timeOutputValue());
    Field<vector>::operator=(d* directions_);
    fixedValuePointPatchField<vector>::updateCoeffs();
  }

  void write(Ostream& os) const override {
    pointPatchField<vector>::write(os);
    os.writeEntry("origin", origin_);
    os.writeEntry("axis", axis_);
    displacement_->writeData(os);
    writeEntry("value", os);
  }

 private:
  /// The unit radial direction at every patch point. The points are where the mesh is now;
  /// a point that only ever moved radially has the direction it started with.
  vectorField radial_directions(const dictionary& dict) const {
    const pointField& points = this->patch().localPoints();
    vectorField directions(points - origin_);
    directions -= axis_ * (axis_ & directions);
    forAll(directions, i) {
      const scalar length = mag(directions[i]);
      if (length < SMALL)
        FatalIOErrorInFunction(dict)
            << "point " << points[i] << " of patch " << this->patch().name()
            << " lies on the axis: it has no radial direction" << exit(FatalIOError);
      directions[i] /= length;
    }
    return directions;
  }

  vector origin_;
  vector axis_;
  autoPtr<Function1<scalar>> displacement_;
  vectorField directions_;
};

makePointPatchTypeField(pointPatchVectorField, cocoppRadialDisplacementPointPatchVectorField);

}  // namespace Foam

#pragma once
// PatchNumbering: one interface patch in the order the coupler sees it, the same in serial and
// in parallel runs: points and faces sorted by their label in the undecomposed mesh. It maps a
// rank's own patch points and faces to positions in that order, and gathers face values on
// the master rank. The constructor is collective (every rank calls it); in a serial run it
// sorts by the mesh's own labels.
#include <vector>

#include "fvCFD.H"

namespace cocopp::openfoam {

class PatchNumbering {
 public:
  /// `point_labels`, `face_labels`: the undecomposed mesh's label of each of this rank's mesh
  /// points and faces (identity in a serial run; decomposePar's addressing in parallel).
  PatchNumbering(const Foam::polyPatch& patch, const Foam::labelUList& point_labels,
                 const Foam::labelUList& face_labels);

  /// Labels of all points (faces) of the patch, sorted: the coupler's order (on every rank).
  const std::vector<Foam::label>& point_ids() const { return point_ids_; }
  const std::vector<Foam::label>& face_ids() const { return face_ids_; }
  /// Position in point_ids() of each of this rank's patch points (patch.meshPoints() order).
  const Foam::labelList& local_point_positions() const { return rank_point_positions_[me()]; }

  /// The values of this rank's points (faces), `components` per point (face), gathered on the
  /// master in the coupler's order; empty on the other ranks. Collective.
  std::vector<double> gather_points(const Foam::UList<Foam::scalar>& local, int components) const;
  std::vector<double> gather_faces(const Foam::UList<Foam::scalar>& local, int components) const;

 private:
  static Foam::label me() { return Foam::Pstream::myProcNo(); }
  static std::vector<double> gather(const Foam::UList<Foam::scalar>& local, int components,
                                    const Foam::List<Foam::labelList>& positions,
                                    std::size_t count);

  std::vector<Foam::label> point_ids_, face_ids_;
  Foam::List<Foam::labelList> rank_point_positions_, rank_face_positions_;  // per rank
};

/// Vector values (x y z per entry) as a flat list of scalars.
Foam::scalarList flatten(const Foam::UList<Foam::vector>& values);

}  // namespace cocopp::openfoam

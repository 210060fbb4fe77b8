#include "solvers/openfoam/patch_numbering.hpp"

#include <algorithm>

namespace cocopp::openfoam {

using namespace Foam;

namespace {

/// Every rank's list, on every rank.
List<labelList> all_ranks(const labelList& mine) {
  List<labelList> lists(Pstream::nProcs());
  lists[Pstream::myProcNo()] = mine;
  Pstream::gatherList(lists);
  Pstream::scatterList(lists);
  return lists;
}

/// The sorted distinct labels of all ranks and, per rank, the position of each of its labels.
std::vector<label> number(const List<labelList>& per_rank, List<labelList>& positions) {
  std::vector<label> sorted;
  for (const labelList& labels : per_rank)
    sorted.insert(sorted.end(), labels.begin(), labels.end());
  std::sort(sorted.begin(), sorted.end());
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  positions.setSize(per_rank.size());
  forAll(per_rank, rank) {
    positions[rank].setSize(per_rank[rank].size());
    forAll(per_rank[rank], i) positions[rank][i] =
        std::lower_bound(sorted.begin(), sorted.end(), per_rank[rank][i]) - sorted.begin();
  }
  return sorted;
}

}  // namespace

PatchNumbering::PatchNumbering(const polyPatch& patch, const labelUList& point_labels,
                               const labelUList& face_labels) {
  labelList points(patch.nPoints());
  forAll(points, i) points[i] = point_labels[patch.meshPoints()[i]];
  labelList faces(patch.size());
  forAll(faces, i) faces[i] = face_labels[patch.start() + i];
  // Points on processor boundaries belong to several ranks: one entry in the numbering.
  point_ids_ = number(all_ranks(points), rank_point_positions_);
  face_ids_ = number(all_ranks(faces), rank_face_positions_);
}

std::vector<double> PatchNumbering::gather_points(const UList<scalar>& local,
                                                  int components) const {
  return gather(local, components, rank_point_positions_, point_ids_.size());
}

std::vector<double> PatchNumbering::gather_faces(const UList<scalar>& local, int components) const {
  return gather(local, components, rank_face_positions_, face_ids_.size());
}

std::vector<double> PatchNumbering::gather(const UList<scalar>& local, int components,
                                           const List<labelList>& positions, std::size_t count) {
  List<scalarList> values(Pstream::nProcs());
  values[Pstream::myProcNo()] = local;
  Pstream::gatherList(values);
  if (!Pstream::master()) return {};
  std::vector<double> ordered(count * components);
  forAll(values, rank) forAll(positions[rank], i) for (int c = 0; c < components; ++c)
      ordered[positions[rank][i] * components + c] = values[rank][i * components + c];
  return ordered;
}

scalarList flatten(const UList<vector>& values) {
  scalarList flat(3 * values.size());
  forAll(values, i) for (direction d = 0; d < 3; ++d) flat[3 * i + d] = values[i][d];
  return flat;
}

}  // namespace cocopp::openfoam

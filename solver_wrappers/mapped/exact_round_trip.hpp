#pragma once
// ExactRoundTrip: maps a position that the other solver reports (a lubricant film's wall, w at
// its points) onto the inner solver's nodes so that the output mapper carries it back to w
// exactly, wherever node values can give w at all.
//
// Why: the input mapper A alone does not. Interpolating w at the nodes and interpolating back
// (L) cuts the wall's bends at the nodes. A structure driven there and balanced against the
// other solver's load converges to a fixed point w = L (A w + du), which leaves
// du = (I - L A) w. That is a force imbalance of K du, large for a stiff body
// (docs/design/displacement-driven-wire.md). Here the nodes get v = A y instead, with y the
// least-squares solution of L R A y = w nearest to w (R: the inner input nodes' values at the
// inner output nodes). Every converged w is L of the structure's output, so there
// L R v = w to round-off, and du = 0 at the fixed point.
//
// Nodes that the structure does not drive (across the other solver's edge: they barely move
// its points) are held at the displacement they have: their values enter the round trip as
// they are, and only the driven ones are solved for. Otherwise the fixed point would fit the
// driven nodes to values the held ones never take.
#include <Eigen/Core>
#include <Eigen/QR>
#include <vector>

#include "mappers/mapper.hpp"

namespace cocopp {

class ExactRoundTrip {
 public:
  /// `input`: the other side's points -> the inner input nodes; `output`: the inner output
  /// nodes -> the other side's points (both built on the current positions); `rows`: for each
  /// inner output node, its row among the inner input nodes; `points` and `components`: of w.
  void build(const Mapper& input, const std::vector<Eigen::Index>& rows, const Mapper& output,
             Eigen::Index points, int components);

  /// Which inner output nodes the inner solver holds (sets itself). None after build().
  void hold(const std::vector<bool>& held);

  /// v at the inner input nodes, one row each, for w at the other side's points. `base`: per
  /// inner output node, what the output mapper adds to a driven node's value (the frame's
  /// motion) and a held node has (its displacement, plus that motion); empty: zero.
  /// Factorises the round trip first if build() or hold() changed it.
  RowMatrix map(const RowMatrix& w, const RowMatrix& base = RowMatrix());

  /// The largest |L R A w - w| of the input mapper alone, and |L R v - w| of map(), in the
  /// last map(): how far the plain round trip misses, and what is left (at a step's
  /// converged iterate, round-off).
  double plain_defect() const { return plain_defect_; }
  double defect() const { return defect_; }

 private:
  void factorise();
  /// The round trip L (P R A y + base) of y at the other side's points (P: zero at the held
  /// nodes), and its linear part L P R A as a matrix on w's entries (row-major, point by point).
  Eigen::VectorXd round_trip(const Eigen::VectorXd& y, const RowMatrix& base) const;
  Eigen::MatrixXd round_trip_matrix() const;
  RowMatrix to_inner(const Eigen::VectorXd& w) const;

  const Mapper* input_ = nullptr;
  const Mapper* output_ = nullptr;
  std::vector<Eigen::Index> rows_;
  std::vector<bool> held_;
  bool factorised_ = false;
  Eigen::Index points_ = 0;
  int components_ = 0;
  /// The round trip on the entries it reaches (nonzero rows and columns), factorised.
  std::vector<Eigen::Index> reached_rows_, reached_columns_;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> solver_;
  double plain_defect_ = 0.0, defect_ = 0.0;
};

}  // namespace cocopp

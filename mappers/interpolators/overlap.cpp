// overlap: conservative transfer of face values (pressure, traction) along one direction, for
// line interfaces such as the generator of an axisymmetric surface.
//
// Each point is the centre of a face, and the faces of a side tile a line: a face reaches
// halfway to its neighbours, and past the ends of its chain by half the spacing to its one
// neighbour (exact for faces of equal length, as blockMesh and make_case.py write them). A target
// face takes the length-weighted mean of the source faces it overlaps, so that
//   sum over targets of value x length = sum over sources of value x (length covered by targets),
// to round-off: nothing of the source's load is lost or counted twice where faces of the two sides
// partly overlap, and a target face that reaches past the source chain gets zero (ambient) for
// the part outside. Linear interpolation samples the source at target centres instead, which
// misses load peaks narrower than a target face. Both sides must be on the same surface (the
// same radius, for an axisymmetric one), as the length stands for the area.
#include <fmt/format.h>

#include <Eigen/Core>
#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "mappers/interpolators/interpolator.hpp"
#include "mappers/interpolators/sparse_rows.hpp"

namespace cocopp {
namespace {

/// The faces of one side along the line: bounds per point, and the points sorted by centre.
struct Faces {
  std::vector<Eigen::Index> order;  ///< point indices by increasing centre
  Eigen::VectorXd lower, upper;     ///< per point (original index)

  Faces(const Eigen::VectorXd& centres, const char* side) {
    const Eigen::Index n = centres.size();
    if (n < 2)
      throw std::invalid_argument(fmt::format(
          "interpolator overlap: the {} side has {} point: faces need at least two centres to "
          "have a length",
          side, n));
    order.resize(static_cast<std::size_t>(n));
    std::iota(order.begin(), order.end(), Eigen::Index{0});
    std::sort(order.begin(), order.end(),
              [&](Eigen::Index a, Eigen::Index b) { return centres(a) < centres(b); });
    lower.resize(n);
    upper.resize(n);
    for (std::size_t k = 0; k + 1 < order.size(); ++k) {
      const double middle = 0.5 * (centres(order[k]) + centres(order[k + 1]));
      upper(order[k]) = middle;
      lower(order[k + 1]) = middle;
    }
    const Eigen::Index first = order.front(), last = order.back();
    lower(first) = centres(first) - (upper(first) - centres(first));
    upper(last) = centres(last) + (centres(last) - lower(last));
  }
};

class Overlap : public Interpolator {
 public:
  using Interpolator::Interpolator;

 protected:
  void build(const Eigen::MatrixXd& source, const Eigen::MatrixXd& target) override {
    if (source.cols() != 1)
      throw std::invalid_argument(fmt::format(
          "interpolator overlap maps along one direction, {} are selected: give one, e.g. "
          "'directions: [y]' for the axis of an axisymmetric surface",
          source.cols()));
    const Faces from(source.col(0), "source"), to(target.col(0), "target");
    // Source upper bounds in sorted order, to find the first source face a target reaches.
    std::vector<double> sorted_upper;
    sorted_upper.reserve(from.order.size());
    for (const Eigen::Index s : from.order) sorted_upper.push_back(from.upper(s));
    const double chain_lower = from.lower(from.order.front());
    const double chain_upper = from.upper(from.order.back());

    SparseRows rows(target.rows(), source.rows(), 4);
    Eigen::VectorXd distances(target.rows());
    int unmatched = 0;
    for (Eigen::Index t = 0; t < target.rows(); ++t) {
      const double low = to.lower(t), high = to.upper(t), length = high - low;
      auto k = static_cast<std::size_t>(
          std::upper_bound(sorted_upper.begin(), sorted_upper.end(), low) - sorted_upper.begin());
      bool any = false;
      for (; k < from.order.size(); ++k) {
        const Eigen::Index s = from.order[k];
        if (from.lower(s) >= high) break;
        const double shared = std::min(high, from.upper(s)) - std::max(low, from.lower(s));
        if (shared <= 0.0) continue;
        rows.add(s, shared / length);
        any = true;
      }
      rows.end_row();
      unmatched += any ? 0 : 1;
      distances(t) = any ? 0.0 : std::max(chain_lower - high, low - chain_upper);
    }
    matrix_ = rows.finish();
    record_distances(distances);
    quality_.unmatched = unmatched;
  }
};

}  // namespace

COCOPP_REGISTER(InterpolatorRegistry, "overlap", Overlap)

}  // namespace cocopp

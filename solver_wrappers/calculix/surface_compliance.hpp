#pragma once
// SurfaceCompliance: the structure's compliance between the lines of nodes the displacement
// drive moves as one (a sector's hoop lines), read from a file the case provides
// (`surface_compliance`, docs/solver-wrappers-calculix.md): the driven direction's displacement
// of each line per unit force on another, the force spread over the line's nodes as a uniform
// traction's nodal forces are (m/N). The drive's Newton step then takes the structure's
// stiffness between the driven lines (the inverse of their compliance, the other lines
// loaded) instead of one local stiffness per line: a smooth push, which a body resists far
// less than a short one, is corrected in one step.
//
// The file (text; examples/wire_drawing/surface_compliance.py writes one):
//   # comment lines
//   lines <L>
//   <the node ids of line 1>
//   ...                                   (L lines)
//   compliance <L>
//   <L numbers>                           (L rows, m/N)
#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <vector>

namespace cocopp::calculix {

class SurfaceCompliance {
 public:
  /// Reads `file`; throws DeckError naming the file and line for anything malformed.
  static SurfaceCompliance read(const std::filesystem::path& file);

  /// The row of the line `node` belongs to, if the file has it.
  std::optional<Eigen::Index> row_of(std::int64_t node) const;
  /// The compliance between the given rows (in their order).
  Eigen::MatrixXd block(const std::vector<Eigen::Index>& rows) const;
  Eigen::Index lines() const { return matrix_.rows(); }

 private:
  std::map<std::int64_t, Eigen::Index> row_of_;
  Eigen::MatrixXd matrix_;
};

}  // namespace cocopp::calculix

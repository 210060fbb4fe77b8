#pragma once
// Reading ccx's .dat file: the nodal values a *NODE PRINT card printed. The .dat file holds 7
// significant digits (the .frd file only 5, in single precision): enough for a coupling residual.
#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/data/interface.hpp"

namespace cocopp::calculix {

/// The last block of `quantity` (e.g. "displacements") printed for node set `set` in `file`,
/// as one row (3 components) per node of `nodes`, in that order. Throws std::runtime_error
/// naming the file, set and missing node if anything is missing or malformed.
RowMatrix read_node_print(const std::filesystem::path& file, const std::string& quantity,
                          const std::string& set, const std::vector<std::int64_t>& nodes);

}  // namespace cocopp::calculix

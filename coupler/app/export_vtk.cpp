#include "coupler/app/export_vtk.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "coupler/results/results_reader.hpp"
#include "coupler/results/vtk_series.hpp"

namespace cocopp {

namespace {

/// One interface's model parts as a results file stores them, with the values of `row`,
/// merged into `parts` by model part (as vtk_parts() does for a running case).
void add_interface(const ResultsReader& reader, const std::string& interface, std::size_t row,
                   std::vector<VtkPart>& parts) {
  if (!reader.has(interface)) return;
  const auto block_parts = reader.strings(interface, "block_model_part");
  const auto block_variables = reader.strings(interface, "block_variable");
  const auto block_components = reader.numbers(interface, "block_components");
  for (std::size_t b = 0; b < block_parts.size(); ++b) {
    const std::string group = interface + "/" + block_parts[b];
    const auto ids_array = reader.dataset(group + "/ids");
    std::vector<std::int64_t> ids(ids_array.values.begin(), ids_array.values.end());
    auto part = std::find_if(parts.begin(), parts.end(), [&](const VtkPart& p) {
      return p.name == block_parts[b] && p.ids == ids;
    });
    if (part == parts.end()) {
      const auto coordinates = reader.dataset(group + "/coordinates");
      Coordinates xyz(static_cast<Eigen::Index>(ids.size()), 3);
      std::copy(coordinates.values.begin(), coordinates.values.end(), xyz.data());
      parts.push_back({block_parts[b], ids, xyz, {}});
      part = parts.end() - 1;
    }
    const auto values = reader.dataset(group + "/" + block_variables[b]);
    const std::size_t size = values.row_size();
    // The components from the layout, not size / points: a model part may have no points.
    RowMatrix field(static_cast<Eigen::Index>(ids.size()),
                    static_cast<Eigen::Index>(block_components.at(b)));
    std::copy_n(values.values.begin() + static_cast<std::ptrdiff_t>(row * size), size,
                field.data());
    part->fields.emplace_back(block_variables[b], std::move(field));
  }
}

}  // namespace

int export_vtk(const std::filesystem::path& results_file,
               const std::filesystem::path& output_directory) {
  try {
    const ResultsReader reader(results_file);
    const std::vector<int> steps = reader.steps();
    const auto times = reader.dataset("steps/time").values;
    const auto directory = output_directory.empty() ? results_file.parent_path() : output_directory;
    VtkSeries series(directory.empty() ? "." : directory, results_file.stem().string());
    for (std::size_t row = 0; row < steps.size(); ++row) {
      std::vector<VtkPart> parts;
      add_interface(reader, "x", row, parts);
      add_interface(reader, "y", row, parts);
      series.write_step(steps[row], times[row], parts);
    }
    fmt::print("{}: {} steps, {} files; open {} in ParaView\n", results_file.string(), steps.size(),
               series.files_written(), series.collection().string());
    return 0;
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 1;
  }
}

}  // namespace cocopp

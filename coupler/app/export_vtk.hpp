#pragma once
// `cocopp export-vtk results.h5`: the interface of every step of a results file as the VTU
// files and PVD collection a run with `settings.vtk_output` writes (VtkSeries), after the fact.
#include <filesystem>

namespace cocopp {

/// Writes <output_directory>/<stem>.pvd and <stem>_vtk/ (output_directory: the results file's
/// own directory when empty). Returns the exit code: 0, or 1 with the error printed.
int export_vtk(const std::filesystem::path& results_file,
               const std::filesystem::path& output_directory);

}  // namespace cocopp

#pragma once
// `cocopp plot`: the plotting scripts behind one subcommand, from the installed package.
#include <filesystem>
#include <string>
#include <vector>

namespace cocopp {

/// <prefix>/share/cocopp/<name> beside the running executable (<prefix>/bin/cocopp), in the
/// build tree and in an install alike: an installed cocopp never reaches into the sources.
std::filesystem::path shared_script(const std::string& name);
/// <prefix>/share/doc/cocopp/<page>, the same way: the docs the help points to (in the build
/// tree a link to the sources' docs/).
std::string documentation(const std::string& page);

/// Draws `file` with the script for its kind, run by Debian's python3 (where matplotlib and
/// h5py install) with `arguments` after the file: a results file (.h5) with plot_results.py,
/// a bench's bench.json with plot_bench.py. Returns the script's exit code; 2 for a file of
/// another kind, 1 if python3 cannot be started (each with a message).
int plot_file(const std::filesystem::path& file, const std::vector<std::string>& arguments);

}  // namespace cocopp

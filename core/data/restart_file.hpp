#pragma once
// Restart files of solvers that keep their state in a few arrays (the tube solvers, the
// calculix wrapper's interface): what a solver needs to continue after a time step, written
// when the coupler saves its state and read back when it restarts the run. One text file per
// solver and step, restart/<solver>_<step>.restart in the solver's working directory, with the
// values as hexadecimal floats ("%a"), so that a restarted run continues bit for bit.
#include <Eigen/Dense>
#include <filesystem>
#include <map>
#include <string>

namespace cocopp {

/// Named arrays of a model's state.
using RestartData = std::map<std::string, Eigen::VectorXd>;

/// "restart/<solver>_<step padded to 6 digits>.restart"
std::filesystem::path restart_file_name(const std::string& solver, int step);

/// Writes the file through a temporary file and a rename, so a solver killed while writing
/// leaves no half file under the final name. Throws std::runtime_error naming the file.
void write_restart_file(const std::filesystem::path& file, const std::string& solver, int step,
                        const RestartData& data);

/// Reads a file written by write_restart_file for `solver` and `step`; throws
/// std::runtime_error naming the file (and line) if it is missing, for another solver or
/// step, or damaged.
RestartData read_restart_file(const std::filesystem::path& file, const std::string& solver,
                              int step);

/// The array `name` of `data` with `size` values; throws std::runtime_error naming the file
/// otherwise (a restart file of a model with another number of cells).
const Eigen::VectorXd& restart_array(const RestartData& data, const std::string& name,
                                     Eigen::Index size, const std::filesystem::path& file);

}  // namespace cocopp

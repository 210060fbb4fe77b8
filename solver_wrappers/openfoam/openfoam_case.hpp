#pragma once
// Reading what the coupler needs to know of an OpenFOAM case before starting the solver:
// entries of dictionaries (controlDict, dynamicMeshDict, transportProperties) and the patch
// names of constant/polyMesh/boundary, with file:line in every error. A small reader of
// OpenFOAM's dictionary syntax (comments, keyword value; entries, sub-dictionaries { }, lists
// ( )); macros ($var, #include) are kept as plain text and not expanded.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/case/settings.hpp"

namespace cocopp::openfoam {

/// The top-level entries of one OpenFOAM dictionary file.
class FoamDictionary {
 public:
  /// Throws CaseError naming the file if it does not exist or is malformed.
  static FoamDictionary read(const std::filesystem::path& file);

  const std::filesystem::path& file() const { return file_; }
  bool has(const std::string& keyword) const { return entries_.count(keyword) > 0; }
  /// The value of a `keyword value;` entry (tokens joined by spaces); nullopt if absent.
  std::optional<std::string> value(const std::string& keyword) const;
  /// "file:line" of the entry (or of the file, if absent), for messages.
  std::string where(const std::string& keyword) const;
  /// A number entry; throws CaseError naming the file and line if absent or not a number.
  double number(const std::string& keyword) const;

 private:
  struct Entry {
    std::string value;
    int line = 0;
  };
  std::filesystem::path file_;
  std::map<std::string, Entry> entries_;
};

/// The patch names of a constant/polyMesh/boundary file, in order.
std::vector<std::string> read_boundary_patches(const std::filesystem::path& boundary_file);

/// Checks an OpenFOAM case for a coupled cocoppPimpleFoam run; every failure is a CaseError
/// that names the file (and line) to change.
struct CaseCheck {
  std::filesystem::path case_directory;
  std::vector<std::string> interface_patches;
  double delta_t = 0.0;  ///< the fluid's time step: the coupler's over the substeps
  std::string solver;    ///< "solver 'flow': ", prefixed to messages
  int cores = 1;         ///< > 1: system/decomposeParDict must split the mesh into as many parts
  void run() const;

 private:
  void check_decomposition() const;
};

}  // namespace cocopp::openfoam

#pragma once
// A fresh copy of an HDF5 file with its extendible datasets cut to the rows a restart keeps.
#include <hdf5.h>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace cocopp::hdf5 {

/// How many of an extendible dataset's `rows` to copy, by the dataset's path ("steps/time").
using RowsToKeep = std::function<hsize_t(const std::string& dataset, hsize_t rows)>;

/// Writes `to` (replaced if it exists) with the groups, datasets and attributes of `from`, in
/// their creation order, each dataset with its type and creation properties. A dataset whose
/// first dimension is unlimited (a series over the steps) is copied up to `keep` rows; links
/// named in `skip` (from the root) are left out.
///
/// It reads only what it keeps and writes everything anew: a file whose writer was killed in a
/// flush can hold metadata (the end-of-file address, a chunk index) that reading the steps
/// flushed before tolerates but writing to the file does not.
void copy_file(const std::filesystem::path& from, const std::filesystem::path& to,
               const RowsToKeep& keep, const std::vector<std::string>& skip);

}  // namespace cocopp::hdf5

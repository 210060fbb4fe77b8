#pragma once
// Helpers of the OpenFOAM tests: making a case's mesh, and reading what OpenFOAM writes (list
// files, internal fields, a patch's values) as flat lists of numbers.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include "tests/support/run_in.hpp"

namespace cocopp::testing {

/// A fresh copy of the OpenFOAM case `case_template` with its mesh, in `directory`.
inline void make_case(const std::filesystem::path& case_template,
                      const std::filesystem::path& directory) {
  std::filesystem::copy(case_template, directory, std::filesystem::copy_options::recursive);
  run_in(directory, "blockMesh");
}

/// The numbers of the first list "( ... )" after `from` in `text`, nested lists flattened:
/// a scalar list gives its values, a vector list x y z per vector.
inline std::vector<double> list_after(const std::string& text, std::size_t from) {
  std::size_t open = text.find('(', from);
  EXPECT_NE(open, std::string::npos);
  std::vector<double> values;
  int depth = 0;
  for (std::size_t i = open; i < text.size(); ++i) {
    if (text[i] == '(') ++depth;
    if (text[i] == ')' && --depth == 0) break;
    if (std::isdigit(static_cast<unsigned char>(text[i])) || text[i] == '-') {
      std::size_t used = 0;
      values.push_back(std::stod(text.substr(i, 40), &used));
      i += used - 1;
    }
  }
  return values;
}

/// An OpenFOAM list file (polyMesh/points, owner): the list after the FoamFile header.
inline std::vector<double> read_list_file(const std::filesystem::path& file) {
  const std::string text = read_text(file);
  return list_after(text, text.find('}', text.find("FoamFile")));
}

inline std::vector<double> read_internal_field(const std::filesystem::path& file) {
  const std::string text = read_text(file);
  const std::size_t entry = text.find("internalField");
  EXPECT_NE(text.find("nonuniform", entry), std::string::npos) << file;
  return list_after(text, entry);
}

inline std::vector<double> read_patch_values(const std::filesystem::path& file,
                                             const std::string& patch) {
  const std::string text = read_text(file);
  std::smatch match;
  const std::string boundary = text.substr(text.find("boundaryField"));
  EXPECT_TRUE(std::regex_search(boundary, match, std::regex("\\b" + patch + "\\s*\\{"))) << file;
  return list_after(boundary, boundary.find("value", match.position()));
}

}  // namespace cocopp::testing

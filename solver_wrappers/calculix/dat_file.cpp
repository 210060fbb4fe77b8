#include "solver_wrappers/calculix/dat_file.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include "solver_wrappers/calculix/input_deck.hpp"

namespace cocopp::calculix {

namespace {

/// ccx's header line: " displacements (vx,vy,vz) for set IFACE and time  0.1000000E+01".
bool is_header_for(const std::string& line, const std::string& quantity, const std::string& set) {
  std::istringstream words(line);
  std::string first;
  if (!(words >> first) || first != quantity) return false;
  const auto at = line.find(" for set ");
  if (at == std::string::npos) return false;
  std::istringstream rest(line.substr(at + 9));
  std::string name;
  rest >> name;
  return name == upper(set);
}

}  // namespace

RowMatrix read_node_print(const std::filesystem::path& file, const std::string& quantity,
                          const std::string& set, const std::vector<std::int64_t>& nodes) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot read ccx's results file " + file.string());
  // Keep the lines of the last matching block: the values at the end of the step.
  std::vector<std::string> block;
  bool found = false;
  bool inside = false;
  std::string line;
  while (std::getline(in, line)) {
    if (is_header_for(line, quantity, set)) {
      found = true;
      inside = true;
      block.clear();
      continue;
    }
    if (!inside) continue;
    if (line.find_first_not_of(" \t\r") == std::string::npos) {
      if (!block.empty()) inside = false;  // the blank line after the values ends the block
      continue;
    }
    block.push_back(line);
  }
  if (!found)
    throw std::runtime_error(file.string() + " has no " + quantity + " for node set " + set +
                             " (ccx printed none: did the step end early?)");
  std::unordered_map<std::int64_t, Eigen::Vector3d> values;
  for (const auto& text : block) {
    std::istringstream fields(text);
    long long id = 0;
    Eigen::Vector3d value;
    if (!(fields >> id >> value[0] >> value[1] >> value[2]))
      throw std::runtime_error(file.string() + ": unreadable " + quantity + " line '" + text +
                               "' for node set " + set);
    values[id] = value;
  }
  RowMatrix result(static_cast<Eigen::Index>(nodes.size()), 3);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const auto value = values.find(nodes[i]);
    if (value == values.end())
      throw std::runtime_error(file.string() + ": no " + quantity + " of node " +
                               std::to_string(nodes[i]) + " in the block for node set " + set);
    result.row(static_cast<Eigen::Index>(i)) = value->second.transpose();
  }
  return result;
}

}  // namespace cocopp::calculix

#include "core/data/calculix_interface_file.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace cocopp::calculix {

std::string ccx_number(double value) {
  // ccx reads a number from the first 20 characters of its field and fails on (or, worse,
  // silently truncates) longer text: 14 significant digits fit, far more than the .dat file's
  // 7 that come back.
  if (std::abs(value) < 1e-99) return "0.";
  char text[32];
  std::snprintf(text, sizeof text, "%.13E", value);
  return text;
}

void InterfaceFile::write(const std::filesystem::path& file) const {
  std::ofstream out(file);
  out << "amplitude " << (ramp ? "ramp" : "step") << "\n";
  out << "initial_increment " << ccx_number(initial_increment) << "\n";
  out << "force_scale " << ccx_number(force_scale) << "\n";
  out << "linear " << (linear ? 1 : 0) << "\n";
  out << "pressure_faces " << pressure_faces.size() << " " << face_offset << "\n";
  for (const auto& [element, face] : pressure_faces) out << element << " " << face << "\n";
  out << "force_nodes " << force_nodes.size() << " " << force_dofs << "\n";
  for (const int node : force_nodes) out << node << "\n";
  out << "displacement_nodes " << displacement_nodes.size() << "\n";
  for (const int node : displacement_nodes) out << node << "\n";
  if (!out.flush()) throw std::runtime_error("cannot write " + file.string());
}

InterfaceFile InterfaceFile::read(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in)
    throw std::runtime_error("cannot read " + file.string() + " (the calculix wrapper writes it)");
  InterfaceFile lists;
  std::string key;
  const auto expect = [&](const char* wanted) {
    if (!(in >> key) || key != wanted)
      throw std::runtime_error(file.string() + ": expected '" + wanted + "', found '" + key + "'");
  };
  // A count is bounded by what the rest of the file can hold (a line per entry).
  const auto read_count = [&]() {
    long long count = -1;
    in >> count;
    if (!in || count < 0 || count > 100'000'000)
      throw std::runtime_error(file.string() + ": '" + key + "' needs a count of 0 or more");
    return static_cast<std::size_t>(count);
  };
  // After each entry: a value it lacks or that is not a number.
  const auto check = [&](const char* entry) {
    if (!in)
      throw std::runtime_error(file.string() + ": '" + entry +
                               "' is truncated or not a number where one belongs");
  };
  std::string amplitude;
  expect("amplitude");
  in >> amplitude;
  if (amplitude != "ramp" && amplitude != "step")
    throw std::runtime_error(file.string() + ": amplitude is ramp or step, not '" + amplitude +
                             "'");
  lists.ramp = amplitude == "ramp";
  expect("initial_increment");
  in >> lists.initial_increment;
  check("initial_increment");
  expect("force_scale");
  in >> lists.force_scale;
  check("force_scale");
  expect("linear");
  int linear = 0;
  in >> linear;
  check("linear");
  lists.linear = linear != 0;
  expect("pressure_faces");
  lists.pressure_faces.resize(read_count());
  in >> lists.face_offset;
  for (auto& [element, face] : lists.pressure_faces) in >> element >> face;
  check("pressure_faces");
  expect("force_nodes");
  lists.force_nodes.resize(read_count());
  in >> lists.force_dofs;
  for (auto& node : lists.force_nodes) in >> node;
  check("force_nodes");
  expect("displacement_nodes");
  lists.displacement_nodes.resize(read_count());
  for (auto& node : lists.displacement_nodes) in >> node;
  check("displacement_nodes");
  return lists;
}

}  // namespace cocopp::calculix

#include "coupler/results/vtk_series.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace cocopp {

namespace {

/// `text` written to `file` through a temporary file in the same directory and a rename.
void write_atomically(const std::filesystem::path& file, const std::string& text) {
  const std::filesystem::path temporary = file.string() + ".writing";
  std::filesystem::remove(temporary);
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << text;
    out.close();
    if (!out) throw std::runtime_error("cannot write " + temporary.string());
  }
  std::filesystem::rename(temporary, file);
}

/// Round-trip exact numbers ("%.17g"), `per_line` to a line.
template <class Values>
void append_numbers(std::string& out, const Values& values, Eigen::Index count, int per_line) {
  for (Eigen::Index i = 0; i < count; ++i) {
    out += fmt::format("{}{:.17g}", i % per_line == 0 ? "\n          " : " ", values(i));
  }
  out += "\n        ";
}

/// A model part's name in a file name: solvers name their model parts, so anything but
/// letters, digits, '_', '-' and '.' becomes '_' (no path can come out of it).
std::string file_name_part(const std::string& name) {
  std::string out = name.empty() ? "part" : name;
  for (char& c : out)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) c = '_';
  if (out.front() == '.') out.front() = '_';
  return out;
}

std::string xml_escaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string vtu(const VtkPart& part) {
  const auto n = static_cast<Eigen::Index>(part.ids.size());
  std::string out =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n  <UnstructuredGrid>\n";
  out += fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", n, n);
  out +=
      "      <Points>\n        <DataArray type=\"Float64\" NumberOfComponents=\"3\" "
      "format=\"ascii\">";
  const Eigen::Map<const Eigen::VectorXd> coordinates(part.coordinates.data(), 3 * n);
  append_numbers(out, coordinates, 3 * n, 3);
  out += "</DataArray>\n      </Points>\n      <Cells>\n";
  // One vertex cell per point: ParaView draws points only when they are cells.
  std::string connectivity, offsets, types;
  for (Eigen::Index i = 0; i < n; ++i) {
    connectivity += fmt::format(" {}", i);
    offsets += fmt::format(" {}", i + 1);
    types += " 1";
  }
  out += "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">" +
         connectivity + "</DataArray>\n";
  out += "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">" + offsets +
         "</DataArray>\n";
  out += "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">" + types +
         "</DataArray>\n      </Cells>\n      <PointData>\n";
  out += "        <DataArray type=\"Int64\" Name=\"id\" format=\"ascii\">";
  for (const auto id : part.ids) out += fmt::format(" {}", id);
  out += "</DataArray>\n";
  for (const auto& [variable, values] : part.fields) {
    out += fmt::format(
        "        <DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\" "
        "format=\"ascii\">",
        xml_escaped(variable), values.cols());
    const Eigen::Map<const Eigen::VectorXd> flat(values.data(), values.size());
    append_numbers(out, flat, values.size(), static_cast<int>(values.cols()));
    out += "</DataArray>\n";
  }
  out += "      </PointData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  return out;
}

}  // namespace

void add_vtk_fields(std::vector<VtkPart>& parts, const Interface& values,
                    const std::string& prefix) {
  for (const auto& part : values.parts()) {
    const ModelPart& model_part = *part.model_part;
    auto same = std::find_if(parts.begin(), parts.end(), [&](const VtkPart& p) {
      return p.name == model_part.name && p.ids == model_part.ids;
    });
    if (same == parts.end()) {
      parts.push_back({model_part.name, model_part.ids, model_part.coordinates, {}});
      same = parts.end() - 1;
    }
    for (const auto& variable : part.variables)
      same->fields.emplace_back(prefix + variable, values.values(model_part.name, variable));
  }
}

std::vector<VtkPart> vtk_parts(const Interface& x, const Interface& y) {
  std::vector<VtkPart> parts;
  add_vtk_fields(parts, x, "");
  add_vtk_fields(parts, y, "");
  return parts;
}

VtkSeries::VtkSeries(std::filesystem::path directory, std::string name, int continue_after_step)
    : directory_(std::move(directory)),
      name_(std::move(name)),
      collection_(directory_ / (name_ + ".pvd")) {
  std::filesystem::create_directories(directory_ / (name_ + "_vtk"));
  if (continue_after_step < 0 || !std::filesystem::exists(collection_)) return;
  // The entries this writer wrote before: one per line, with the step in the file name.
  std::ifstream in(collection_);
  const std::regex entry(
      R"re(timestep="([^"]+)" part="(\d+)" name="([^"]*)" file="([^"]*_(\d+)\.vtu)")re");
  std::string line;
  std::smatch match;
  while (std::getline(in, line))
    if (std::regex_search(line, match, entry)) {
      const int step = std::stoi(match[5]);
      if (step > continue_after_step) continue;
      part_index(match[3]);
      entries_.push_back({step, std::stod(match[1]), std::stoi(match[2]), match[3], match[4]});
    }
}

int VtkSeries::part_index(const std::string& name) {
  const auto found = std::find(part_names_.begin(), part_names_.end(), name);
  if (found != part_names_.end()) return static_cast<int>(found - part_names_.begin());
  part_names_.push_back(name);
  return static_cast<int>(part_names_.size()) - 1;
}

void VtkSeries::write_step(int step, double time, const std::vector<VtkPart>& parts) {
  for (const VtkPart& part : parts) {
    const std::string file =
        fmt::format("{}_vtk/{}_{:06d}.vtu", name_, file_name_part(part.name), step);
    write_atomically(directory_ / file, vtu(part));
    ++files_written_;
    entries_.push_back({step, time, part_index(part.name), part.name, file});
  }
  write_collection();
}

void VtkSeries::write_collection() const {
  std::string out =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" "
      "byte_order=\"LittleEndian\">\n  <Collection>\n";
  for (const Entry& e : entries_)
    out += fmt::format("    <DataSet timestep=\"{:.17g}\" part=\"{}\" name=\"{}\" file=\"{}\"/>\n",
                       e.time, e.part, xml_escaped(e.part_name), e.file);
  out += "  </Collection>\n</VTKFile>\n";
  write_atomically(collection_, out);
}

}  // namespace cocopp

#include "solvers/tube/tube_output.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace cocopp::tube {

std::string output_file_name(const OutputSettings& output, const std::string& solver, int step) {
  char number[32];
  std::snprintf(number, sizeof number, "%06d", step);
  return (std::filesystem::path(output.directory) / (solver + "_" + number + ".vtk")).string();
}

Eigen::VectorXd radial_vectors(const Eigen::VectorXd& displacement) {
  Eigen::VectorXd vectors = Eigen::VectorXd::Zero(3 * displacement.size());
  for (Eigen::Index i = 0; i < displacement.size(); ++i) vectors[3 * i + 1] = displacement[i];
  return vectors;
}

void write_output(const OutputSettings& output, const std::string& solver, int step, double time,
                  const TubeGeometry& geometry, const Eigen::VectorXd& displacement,
                  const std::vector<PointField>& fields) {
  if (!output.due(step)) return;
  std::filesystem::create_directories(output.directory);
  const std::string file_name = output_file_name(output, solver, step);
  std::ofstream file(file_name);
  if (!file) throw std::runtime_error(file_name + ": cannot write the output file");
  file.precision(std::numeric_limits<double>::max_digits10);

  const int m = geometry.cells;
  const Eigen::VectorXd z = geometry.cell_centres();
  file << "# vtk DataFile Version 3.0\n"
       << solver << " step " << step << "\nASCII\nDATASET POLYDATA\n"
       << "FIELD FieldData 1\nTIME 1 1 double\n"
       << time << "\n"
       << "POINTS " << m << " double\n";
  for (int i = 0; i < m; ++i) {
    file << 0.0 << ' ' << geometry.radius() + displacement[i] << ' ' << z[i] << '\n';
  }
  file << "LINES 1 " << m + 1 << '\n' << m;
  for (int i = 0; i < m; ++i) file << ' ' << i;
  file << "\nPOINT_DATA " << m << '\n';
  for (const auto& field : fields) {
    if (field.is_vector) {
      file << "VECTORS " << field.name << " double\n";
      for (int i = 0; i < m; ++i) {
        file << field.values[3 * i] << ' ' << field.values[3 * i + 1] << ' '
             << field.values[3 * i + 2] << '\n';
      }
    } else {
      file << "SCALARS " << field.name << " double 1\nLOOKUP_TABLE default\n";
      for (int i = 0; i < m; ++i) file << field.values[i] << '\n';
    }
  }
  if (!file) throw std::runtime_error(file_name + ": error while writing the output file");
}

}  // namespace cocopp::tube

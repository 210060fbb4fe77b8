#include "core/data/restart_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace cocopp {

namespace {

constexpr const char* kMagic = "cocopp restart 1";

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& message) {
  throw std::runtime_error("restart file " + file.string() + ": " + message);
}

std::string hex(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%a", value);
  return text;
}

double parse_double(const std::string& word, const std::filesystem::path& file, int line) {
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(word.c_str(), &end);
  if (end == word.c_str() || *end != '\0' || errno == ERANGE)
    fail(file, "line " + std::to_string(line) + ": '" + word + "' is not a number");
  return value;
}

}  // namespace

std::filesystem::path restart_file_name(const std::string& solver, int step) {
  char number[32];
  std::snprintf(number, sizeof number, "%06d", step);
  return std::filesystem::path("restart") / (solver + "_" + number + ".restart");
}

void write_restart_file(const std::filesystem::path& file, const std::string& solver, int step,
                        const RestartData& data) {
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  std::filesystem::path temporary = file;
  temporary += ".writing";
  {
    std::ofstream out(temporary, std::ios::trunc);
    if (!out) fail(temporary, "cannot be written");
    out << kMagic << "\nsolver " << solver << "\nstep " << step << "\n";
    for (const auto& [name, values] : data) {
      out << name << " " << values.size();
      for (double value : values) out << " " << hex(value);
      out << "\n";
    }
    out.flush();
    if (!out) fail(temporary, "writing failed (disk full?)");
  }
  std::filesystem::rename(temporary, file);
}

RestartData read_restart_file(const std::filesystem::path& file, const std::string& solver,
                              int step) {
  std::ifstream in(file);
  if (!in)
    fail(file, "not found: the run that saved the coupler's state after step " +
                   std::to_string(step) + " did not save this solver's state with it");
  std::string line;
  std::getline(in, line);
  if (line != kMagic) fail(file, "line 1: not a cocopp restart file");
  std::string key, found_solver;
  int found_step = -1;
  std::getline(in, line);
  std::istringstream(line) >> key >> found_solver;
  std::getline(in, line);
  std::istringstream(line) >> key >> found_step;
  if (found_solver != solver || found_step != step)
    fail(file, "holds " + found_solver + " after step " + std::to_string(found_step) +
                   ", expected " + solver + " after step " + std::to_string(step));
  RestartData data;
  for (int number = 4; std::getline(in, line); ++number) {
    std::istringstream words(line);
    std::string name;
    long long size = -1;
    if (!(words >> name >> size) || size < 0)
      fail(file, "line " + std::to_string(number) + ": expected a name and a count");
    Eigen::VectorXd values(size);
    std::string word;
    for (Eigen::Index i = 0; i < size; ++i) {
      if (!(words >> word))
        fail(file, "line " + std::to_string(number) + ": '" + name + "' has fewer than " +
                       std::to_string(size) + " values");
      values[i] = parse_double(word, file, number);
    }
    data[name] = std::move(values);
  }
  return data;
}

const Eigen::VectorXd& restart_array(const RestartData& data, const std::string& name,
                                     Eigen::Index size, const std::filesystem::path& file) {
  const auto found = data.find(name);
  if (found == data.end()) fail(file, "has no '" + name + "'");
  if (found->second.size() != size)
    fail(file, "'" + name + "' has " + std::to_string(found->second.size()) +
                   " values, this model needs " + std::to_string(size) +
                   " (was the number of cells changed?)");
  return found->second;
}

}  // namespace cocopp

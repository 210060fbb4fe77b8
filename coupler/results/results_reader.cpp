#include "coupler/results/results_reader.hpp"

#include <stdexcept>

namespace cocopp {

using namespace hdf5;

std::size_t ResultsReader::Array::row_size() const {
  return shape.empty() || shape[0] == 0 ? 0 : values.size() / shape[0];
}

namespace {

[[noreturn]] void fail(const std::filesystem::path& file, const std::exception& error) {
  throw std::runtime_error("cannot read the results file " + file.string() + ": " + error.what());
}

/// Runs `read` with HDF5's error printing off; any error becomes one that names the file.
template <class Read>
auto reading(const std::filesystem::path& file, Read read) {
  const QuietErrors quiet;
  try {
    return read();
  } catch (const std::exception& error) {
    fail(file, error);
  }
}

}  // namespace

ResultsReader::ResultsReader(const std::filesystem::path& file) : path_(file) {
  reading(path_, [&] {
    if (!std::filesystem::is_regular_file(file)) throw H5Error("no such file");
    file_ =
        H5Handle(checked(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "opening"), H5Fclose);
    return 0;
  });
}

bool ResultsReader::has(const std::string& object) const {
  if (object.empty()) return false;
  const QuietErrors quiet;
  // H5Lexists needs every parent of the path to exist: walk it from the root.
  std::string path;
  std::size_t start = object.front() == '/' ? 1 : 0;
  while (start <= object.size()) {
    const std::size_t end = std::min(object.find('/', start), object.size());
    path += (path.empty() ? "" : "/") + object.substr(start, end - start);
    if (H5Lexists(file_.get(), path.c_str(), H5P_DEFAULT) <= 0) return false;
    start = end + 1;
  }
  return true;
}

bool ResultsReader::has_attribute(const std::string& object, const std::string& name) const {
  const QuietErrors quiet;
  return (object == "/" || has(object)) &&
         H5Aexists_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT) > 0;
}

H5Handle ResultsReader::open_dataset(const std::string& name) const {
  if (!has(name)) throw H5Error("no dataset " + name);
  return {checked(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT), "opening " + name), H5Dclose};
}

std::vector<std::string> ResultsReader::members(const std::string& group) const {
  if (!has(group)) return {};
  return reading(path_, [&] {
    const H5Handle g(checked(H5Gopen2(file_.get(), group.c_str(), H5P_DEFAULT), "opening " + group),
                     H5Gclose);
    return member_names(g.get());
  });
}

ResultsReader::Array ResultsReader::dataset(const std::string& name) const {
  return reading(path_, [&] {
    const H5Handle dataset = open_dataset(name);
    Array out;
    for (hsize_t n : dataset_shape(dataset.get())) out.shape.push_back(std::size_t(n));
    out.values = read_doubles(dataset.get());
    return out;
  });
}

std::vector<int> ResultsReader::bools(const std::string& name) const {
  return reading(path_, [&] {
    const H5Handle dataset = open_dataset(name);
    const H5Handle type = bool_type();
    std::vector<std::int8_t> raw(element_count(dataset.get()));
    if (!raw.empty())
      checked(H5Dread(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data()),
              "reading " + name);
    return std::vector<int>(raw.begin(), raw.end());
  });
}

std::vector<std::string> ResultsReader::strings(const std::string& object,
                                                const std::string& name) const {
  return reading(path_, [&] { return read_strings_attribute(file_.get(), object, name); });
}

std::string ResultsReader::string(const std::string& object, const std::string& name) const {
  const auto values = strings(object, name);
  return values.empty() ? std::string() : values.front();
}

std::vector<double> ResultsReader::numbers(const std::string& object,
                                           const std::string& name) const {
  return reading(path_, [&] { return read_doubles_attribute(file_.get(), object, name); });
}

double ResultsReader::number(const std::string& object, const std::string& name) const {
  const auto values = numbers(object, name);
  if (values.empty()) fail(path_, H5Error("attribute " + object + "@" + name + " is empty"));
  return values.front();
}

std::vector<int> ResultsReader::steps() const {
  std::vector<int> steps;
  if (!has("steps/step")) return steps;
  for (double step : dataset("steps/step").values) steps.push_back(static_cast<int>(step));
  return steps;
}

std::map<std::string, ResultsReader::Array> ResultsReader::variable(
    const std::string& interface, const std::string& variable) const {
  std::map<std::string, Array> by_part;
  for (const std::string& part : members(interface)) {
    const std::string name = interface + "/" + part + "/" + variable;
    if (has(name)) by_part[part] = dataset(name);
  }
  return by_part;
}

}  // namespace cocopp

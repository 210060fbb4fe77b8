#include "coupler/results/watchpoint_csv.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace cocopp {

namespace {

constexpr const char* kComponentNames[] = {"x", "y", "z"};

std::string header(const Interface& layout, const std::string& part) {
  std::string line = "step,time";
  for (const auto& block : layout.blocks()) {
    if (block.model_part != part) continue;
    if (block.components == 1) line += "," + block.variable;
    for (int c = 0; block.components > 1 && c < block.components; ++c)
      line += "," + block.variable + "_" + kComponentNames[c];
  }
  return line;
}

/// The lines of an earlier run's file up to `step` (header included), or just the header if
/// there is no file.
std::string kept_lines(const std::filesystem::path& path, const std::string& header_line,
                       int step) {
  std::ifstream in(path);
  std::string kept = header_line + "\n", line;
  if (!in || !std::getline(in, line)) return kept;
  if (line != header_line)
    throw std::runtime_error("watchpoint file '" + path.string() + "' has the columns " + line +
                             ", this run writes " + header_line + ": was the case changed?");
  while (std::getline(in, line)) {
    if (std::stoi(line.substr(0, line.find(','))) > step) break;
    kept += line + "\n";
  }
  return kept;
}

}  // namespace

WatchpointCsv::WatchpointCsv(const RunFiles& files, const Interface& layout,
                             int continue_after_step) {
  std::filesystem::create_directories(files.directory);
  for (const auto& part : layout.parts()) {
    const std::string& watchpoint = part.model_part->name;
    const auto path = files.watchpoint_csv(watchpoint);
    const std::string header_line = header(layout, watchpoint);
    const std::string start = continue_after_step >= 0
                                  ? kept_lines(path, header_line, continue_after_step)
                                  : header_line + "\n";
    // A fresh file (a link planted at the name is replaced, never followed).
    std::filesystem::remove(path);
    auto file = std::make_unique<std::ofstream>(path);
    *file << start << std::flush;
    if (!*file) throw std::runtime_error("cannot write watchpoint file '" + path.string() + "'");
    paths_.push_back(path);
    files_.push_back(std::move(file));
  }
}

void WatchpointCsv::write_step(int step, double time, const Interface& values) {
  const auto& parts = values.parts();
  for (std::size_t i = 0; i < files_.size() && i < parts.size(); ++i) {
    std::string line = fmt::format("{},{}", step, time);
    for (const auto& block : values.blocks()) {
      if (block.model_part != parts[i].model_part->name) continue;
      for (Eigen::Index k = 0; k < block.components; ++k)
        line += fmt::format(",{}", values.data()[block.offset + k]);
    }
    *files_[i] << line << "\n" << std::flush;
    if (!*files_[i])
      throw std::runtime_error("cannot write watchpoint file '" + paths_[i].string() + "'");
  }
}

}  // namespace cocopp

#include "solver_wrappers/calculix/surface_compliance.hpp"

#include <fmt/format.h>

#include <fstream>
#include <sstream>
#include <string>

#include "solver_wrappers/calculix/input_deck.hpp"

namespace cocopp::calculix {

namespace {

/// Reads the file's lines, comments skipped, with their numbers for messages.
class Lines {
 public:
  explicit Lines(const std::filesystem::path& file) : file_(file), in_(file) {
    if (!in_) throw DeckError(fmt::format("{}: cannot be read", file.string()));
  }
  std::string next(const char* what) {
    std::string text;
    while (std::getline(in_, text)) {
      ++number_;
      if (!text.empty() && text[0] != '#') return text;
    }
    fail(fmt::format("ends before {}", what));
  }
  /// "<keyword> <count>" on the next line.
  Eigen::Index header(const std::string& keyword) {
    std::istringstream words(next(keyword.c_str()));
    std::string word;
    long long count = -1;
    if (!(words >> word >> count) || word != keyword || count <= 0)
      fail(fmt::format("expected '{} <count>'", keyword));
    return static_cast<Eigen::Index>(count);
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw DeckError(fmt::format("{}:{}: surface compliance: {}", file_.string(), number_, what));
  }

 private:
  std::filesystem::path file_;
  std::ifstream in_;
  int number_ = 0;
};

}  // namespace

SurfaceCompliance SurfaceCompliance::read(const std::filesystem::path& file) {
  Lines lines(file);
  SurfaceCompliance result;
  const Eigen::Index count = lines.header("lines");
  for (Eigen::Index row = 0; row < count; ++row) {
    std::istringstream nodes(lines.next("the lines' nodes"));
    std::int64_t node = 0;
    int read = 0;
    while (nodes >> node) {
      if (!result.row_of_.emplace(node, row).second)
        lines.fail(fmt::format("node {} is in two lines", node));
      ++read;
    }
    if (read == 0 || !nodes.eof()) lines.fail("expected the node ids of a line");
  }
  if (lines.header("compliance") != count)
    lines.fail(fmt::format("the compliance must be {0} x {0}, one row and column per line", count));
  result.matrix_.resize(count, count);
  for (Eigen::Index row = 0; row < count; ++row) {
    std::istringstream values(lines.next("the compliance's rows"));
    for (Eigen::Index column = 0; column < count; ++column)
      if (!(values >> result.matrix_(row, column)))
        lines.fail(fmt::format("row {} has fewer than {} numbers", row + 1, count));
    std::string rest;
    if (values >> rest) lines.fail(fmt::format("row {} has more than {} numbers", row + 1, count));
  }
  return result;
}

std::optional<Eigen::Index> SurfaceCompliance::row_of(std::int64_t node) const {
  const auto found = row_of_.find(node);
  if (found == row_of_.end()) return std::nullopt;
  return found->second;
}

Eigen::MatrixXd SurfaceCompliance::block(const std::vector<Eigen::Index>& rows) const {
  const auto n = static_cast<Eigen::Index>(rows.size());
  Eigen::MatrixXd result(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j)
      result(i, j) = matrix_(rows[static_cast<std::size_t>(i)], rows[static_cast<std::size_t>(j)]);
  return result;
}

}  // namespace cocopp::calculix

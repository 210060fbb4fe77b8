#include "solver_wrappers/openfoam/openfoam_case.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/case/path_problem.hpp"
#include "core/case/suggest.hpp"

namespace cocopp::openfoam {

namespace {

struct Token {
  std::string text;
  int line = 0;
};

bool is_punctuation(char c) {
  return c == ';' || c == '{' || c == '}' || c == '(' || c == ')';
}

/// Words, quoted strings and the punctuation ; { } ( ), without comments.
std::vector<Token> tokenize(const std::string& text, const std::filesystem::path& file) {
  std::vector<Token> tokens;
  int line = 1;
  std::size_t i = 0;
  auto at = [&](std::size_t k) { return k < text.size() ? text[k] : '\0'; };
  while (i < text.size()) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      ++i;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (c == '/' && at(i + 1) == '/') {
      while (i < text.size() && text[i] != '\n') ++i;
    } else if (c == '/' && at(i + 1) == '*') {
      const int start_line = line;
      i += 2;
      while (i < text.size() && !(text[i] == '*' && at(i + 1) == '/')) line += text[i++] == '\n';
      if (i >= text.size())
        throw CaseError(fmt::format("{}:{}: unterminated comment", file.string(), start_line));
      i += 2;
    } else if (is_punctuation(c)) {
      tokens.push_back({std::string(1, c), line});
      ++i;
    } else if (c == '"') {
      const std::size_t end = text.find('"', i + 1);
      if (end == std::string::npos)
        throw CaseError(fmt::format("{}:{}: unterminated string", file.string(), line));
      tokens.push_back({text.substr(i, end - i + 1), line});
      for (std::size_t k = i; k < end; ++k) line += text[k] == '\n';
      i = end + 1;
    } else {
      const std::size_t start = i;
      while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i])) &&
             !is_punctuation(text[i]) &&
             !(text[i] == '/' && (at(i + 1) == '/' || at(i + 1) == '*')))
        ++i;
      tokens.push_back({text.substr(start, i - start), line});
    }
  }
  return tokens;
}

std::vector<Token> tokenize_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw CaseError(file.string() + ": cannot read the file (does it exist?)");
  std::stringstream text;
  text << in.rdbuf();
  return tokenize(text.str(), file);
}

/// Index just past the group that opens at tokens[open] ("{" or "(") and its closing match.
std::size_t skip_group(const std::vector<Token>& tokens, std::size_t open,
                       const std::filesystem::path& file) {
  int depth = 0;
  for (std::size_t i = open; i < tokens.size(); ++i) {
    const std::string& t = tokens[i].text;
    if (t == "{" || t == "(") ++depth;
    if (t == "}" || t == ")") --depth;
    if (depth == 0) return i + 1;
  }
  throw CaseError(fmt::format("{}:{}: '{}' is never closed", file.string(), tokens[open].line,
                              tokens[open].text));
}

bool is_false(const std::string& value) {
  return value == "no" || value == "off" || value == "false" || value == "n" || value == "none";
}

}  // namespace

FoamDictionary FoamDictionary::read(const std::filesystem::path& file) {
  const std::vector<Token> tokens = tokenize_file(file);
  FoamDictionary dictionary;
  dictionary.file_ = file;
  std::size_t i = 0;
  while (i < tokens.size()) {
    const Token& keyword = tokens[i];
    if (is_punctuation(keyword.text[0]) && keyword.text.size() == 1)
      throw CaseError(fmt::format("{}:{}: expected a keyword, found '{}'", file.string(),
                                  keyword.line, keyword.text));
    ++i;
    if (i < tokens.size() && tokens[i].text == "{") {  // a sub-dictionary
      i = skip_group(tokens, i, file);
      dictionary.entries_[keyword.text] = {"{...}", keyword.line};
      continue;
    }
    std::string value;
    while (i < tokens.size() && tokens[i].text != ";") {
      const std::size_t next =
          (tokens[i].text == "(" || tokens[i].text == "{") ? skip_group(tokens, i, file) : i + 1;
      for (std::size_t k = i; k < next; ++k) value += (value.empty() ? "" : " ") + tokens[k].text;
      i = next;
    }
    if (i >= tokens.size() && keyword.text[0] != '#')
      throw CaseError(fmt::format("{}:{}: entry '{}' does not end with ';'", file.string(),
                                  keyword.line, keyword.text));
    ++i;  // the ';'
    dictionary.entries_[keyword.text] = {value, keyword.line};
  }
  return dictionary;
}

std::optional<std::string> FoamDictionary::value(const std::string& keyword) const {
  const auto entry = entries_.find(keyword);
  if (entry == entries_.end()) return std::nullopt;
  return entry->second.value;
}

std::string FoamDictionary::where(const std::string& keyword) const {
  const auto entry = entries_.find(keyword);
  return entry == entries_.end() ? file_.string()
                                 : fmt::format("{}:{}", file_.string(), entry->second.line);
}

double FoamDictionary::number(const std::string& keyword) const {
  const auto text = value(keyword);
  if (!text) throw CaseError(file_.string() + ": the entry '" + keyword + "' is missing");
  try {
    std::size_t used = 0;
    const double number = std::stod(*text, &used);
    if (used == text->size()) return number;
  } catch (const std::exception&) {
  }
  throw CaseError(where(keyword) + ": '" + keyword + "' must be a number, not '" + *text + "'");
}

std::vector<std::string> read_boundary_patches(const std::filesystem::path& boundary_file) {
  const std::vector<Token> tokens = tokenize_file(boundary_file);
  // FoamFile { ... }  N  ( name { ... } name { ... } )
  std::size_t i = 0;
  if (i + 1 < tokens.size() && tokens[i].text == "FoamFile" && tokens[i + 1].text == "{")
    i = skip_group(tokens, i + 1, boundary_file);
  while (i < tokens.size() && tokens[i].text != "(") ++i;
  if (i >= tokens.size())
    throw CaseError(boundary_file.string() + ": no list of patches '( ... )' found");
  const std::size_t end = skip_group(tokens, i, boundary_file) - 1;
  std::vector<std::string> patches;
  for (++i; i < end;) {
    if (i + 1 >= end || tokens[i + 1].text != "{")
      throw CaseError(fmt::format("{}:{}: expected a patch name followed by '{{', found '{}'",
                                  boundary_file.string(), tokens[i].line, tokens[i].text));
    patches.push_back(tokens[i].text);
    i = skip_group(tokens, i + 1, boundary_file);
  }
  return patches;
}

void CaseCheck::run() const {
  const auto control_dict = FoamDictionary::read(case_directory / "system" / "controlDict");
  const double case_delta_t = control_dict.number("deltaT");
  if (std::abs(case_delta_t - delta_t) > 1e-9 * std::abs(delta_t))
    throw CaseError(fmt::format(
        "{}: {}deltaT {} differs from the coupler's time step {} (delta_t, divided by the "
        "solver's substeps): they must be equal",
        control_dict.where("deltaT"), solver, case_delta_t, delta_t));
  if (const auto adjust = control_dict.value("adjustTimeStep"); adjust && !is_false(*adjust))
    throw CaseError(
        fmt::format("{}: {}adjustTimeStep {}: the coupler fixes the time step; set it to no",
                    control_dict.where("adjustTimeStep"), solver, *adjust));

  const auto dynamic_mesh = FoamDictionary::read(case_directory / "constant" / "dynamicMeshDict");
  const auto mesh_type = dynamic_mesh.value("dynamicFvMesh");
  if (mesh_type != "dynamicMotionSolverFvMesh")
    throw CaseError(fmt::format(
        "{}: {}dynamicFvMesh is {}: the interface moves the mesh through a motion solver, set "
        "'dynamicFvMesh dynamicMotionSolverFvMesh;' (with e.g. 'solver displacementLaplacian;')",
        dynamic_mesh.where("dynamicFvMesh"), solver, mesh_type ? *mesh_type : "missing"));

  const auto boundary_file = case_directory / "constant" / "polyMesh" / "boundary";
  if (!path_problem(boundary_file, PathKind::kRegularFile).empty())
    throw CaseError(boundary_file.string() + ": " + solver +
                    "the case has no mesh (make it first, e.g. with blockMesh)");
  const std::vector<std::string> patches = read_boundary_patches(boundary_file);
  for (const std::string& patch : interface_patches)
    if (std::find(patches.begin(), patches.end(), patch) == patches.end())
      throw CaseError(fmt::format(
          "{}: {}interface patch '{}' is not in the mesh (its patches: {}){}",
          boundary_file.string(), solver, patch, join(patches), did_you_mean(patch, patches)));

  const auto transport = FoamDictionary::read(case_directory / "constant" / "transportProperties");
  if (!transport.has("rho"))
    throw CaseError(fmt::format(
        "{}: {}the fluid density rho is missing: the loads sent to the coupler are in Pa, the "
        "kinematic pressure and stress times rho (add e.g. 'rho 1000;')",
        transport.file().string(), solver));
  if (cores > 1) check_decomposition();
}

void CaseCheck::check_decomposition() const {
  const auto decompose = FoamDictionary::read(case_directory / "system" / "decomposeParDict");
  const double parts = decompose.number("numberOfSubdomains");
  if (parts != cores)
    throw CaseError(fmt::format(
        "{}: {}numberOfSubdomains {} differs from the solver's cores {}: they must be equal",
        decompose.where("numberOfSubdomains"), solver, parts, cores));
  // Debian's scotch decomposition library is a stub: only the geometric methods work.
  const auto method = decompose.value("method");
  if (method != "simple" && method != "hierarchical")
    throw CaseError(fmt::format("{}: {}method {}: use simple or hierarchical (with their coeffs)",
                                decompose.where("method"), solver, method ? *method : "missing"));
}

}  // namespace cocopp::openfoam

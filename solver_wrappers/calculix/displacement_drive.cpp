#include "solver_wrappers/calculix/displacement_drive.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <tuple>

#include "solver_wrappers/calculix/probed_film.hpp"
#include "solver_wrappers/calculix/reynolds_film.hpp"

namespace cocopp::calculix {

namespace {

/// A face counts as covered by the other solver from this fraction on.
constexpr double kDrivenCoverage = 0.5;

bool is_keyword(const std::string& text) {
  return !text.empty() && text[0] == '*' && (text.size() < 2 || text[1] != '*');
}

bool is_boundary_card(const std::string& text) {
  return is_keyword(text) && upper(text).rfind("*BOUNDARY", 0) == 0;
}

}  // namespace

const std::vector<std::string>& DisplacementDrive::face_variables() {
  static const std::vector<std::string> variables = {"gap", "coverage"};
  return variables;
}

DisplacementDrive::DisplacementDrive(const InputDeck& deck, InterfaceLoads& loads,
                                     std::vector<std::int64_t> interface_nodes,
                                     std::vector<std::int64_t> drivable_nodes, int dof,
                                     double surface_stiffness)
    : deck_(deck),
      loads_(loads),
      interface_nodes_(std::move(interface_nodes)),
      drivable_nodes_(std::move(drivable_nodes)),
      dof_(dof),
      surface_stiffness_(surface_stiffness) {
  for (const auto& face : loads_.faces()) {
    const std::string& type = deck_.element(face.element).type;
    if (type.rfind("CAX", 0) == 0)
      throw DeckError(fmt::format(
          "element {} is a {}: interface_drive: displacement balances the other solver's "
          "loads against ccx's reaction forces, and on an axisymmetric model ccx prints "
          "reactions that are not the forces at the nodes (53 % off on a ring, "
          "examples/wire_drawing/reaction_probe.py). Model the body as a 3D sector instead "
          "(C3D20R with a cylindrical *TRANSFORM and the hoop displacement held)",
          face.element, type));
  }
  for (const auto& line : deck_.step())
    if (is_boundary_card(line.text))
      throw DeckError(line.where +
                      ": *BOUNDARY inside the step: with interface_drive: displacement the "
                      "wrapper rewrites the boundary conditions of every step (*BOUNDARY, "
                      "OP=NEW, then the deck's own): move it before *STEP");
  model_boundary_ = model_boundary_cards(deck_);
  for (std::size_t f = 0; f < loads_.geometry().size(); ++f)
    for (const auto node : loads_.geometry()[f].nodes) faces_of_[node].push_back(f);
}

std::vector<std::string> DisplacementDrive::model_boundary_cards(const InputDeck& deck) const {
  std::vector<std::string> lines;
  bool inside = false;
  for (const auto& line : deck.model_definition()) {
    if (is_keyword(line.text)) inside = is_boundary_card(line.text);
    if (inside && line.text.rfind("**", 0) != 0) lines.push_back(line.text);
  }
  return lines;
}

Eigen::Vector3d DisplacementDrive::direction(std::int64_t node) const {
  if (const NodalTransform* transform = deck_.transform(node))
    return transform->axes_at(deck_.node(node)).row(dof_ - 1).transpose();
  return Eigen::Vector3d::Unit(dof_ - 1);
}

void DisplacementDrive::use_compliance(SurfaceCompliance compliance, double scale) {
  // Every drivable node's line must be one of the file's, whole: a line split between two
  // rows, or half missing, would move its nodes apart.
  for (const auto node : drivable_nodes_)
    if (!compliance.row_of(node))
      throw DeckError(fmt::format(
          "node {} may be driven but is in none of the surface compliance's lines: the file "
          "must list every line of the driven node set",
          node));
  compliance_ = std::move(compliance);
  compliance_scale_ = scale;
}

void DisplacementDrive::plan(const Inputs& inputs, const NodeDisplacements& converged) {
  const auto faces = static_cast<Eigen::Index>(loads_.faces().size());
  const bool totals = inputs.force.size() > 0;
  if ((totals ? inputs.force.rows() != faces
              : inputs.pressure.size() != faces ||
                    (inputs.traction.size() > 0 && inputs.traction.rows() != faces)) ||
      inputs.gap.size() != faces || inputs.coverage.size() != faces ||
      inputs.wall_displacement.rows() != static_cast<Eigen::Index>(drivable_nodes_.size()))
    throw std::invalid_argument(
        "DisplacementDrive::plan: one value per interface face and one wall displacement per "
        "drivable node expected");
  inputs_ = inputs;
  driven_face_.assign(loads_.faces().size(), false);
  for (Eigen::Index f = 0; f < faces; ++f)
    driven_face_[static_cast<std::size_t>(f)] =
        inputs.coverage[f] >= kDrivenCoverage && inputs.gap[f] > 0.0;
  prescribed_.clear();
  for (std::size_t k = 0; k < drivable_nodes_.size(); ++k) {
    const auto node = drivable_nodes_[k];
    const auto found = faces_of_.find(node);
    if (found == faces_of_.end()) continue;
    const auto& faces_of_node = found->second;
    // A node across the other solver's edge stays loaded: it barely moves the other
    // solver's points, so the coupling could not tell its balance (it is reported as
    // `driven` 0, and the mapped wrapper's round trip takes its displacement as it is).
    if (!std::all_of(faces_of_node.begin(), faces_of_node.end(),
                     [&](std::size_t f) { return driven_face_[f]; }))
      continue;
    prescribed_[node] =
        inputs.wall_displacement.row(static_cast<Eigen::Index>(k)).dot(direction(node).transpose());
  }
  // The faces where this iteration puts them, in a step with NLGEOM: the other solver
  // computed its loads on its wall there. (Without, ccx takes loads on the deck's geometry.)
  if (deck_.nonlinear_geometry()) move_faces(converged);
  if (totals) inputs_.pressure = loads_.pressure_of_totals(inputs_.force);
  film_forces_ = totals ? loads_.nodal_forces_of_totals(inputs_.force)
                        : loads_.nodal_forces(inputs_.traction, inputs_.pressure);
}

void DisplacementDrive::move_faces(const NodeDisplacements& converged) {
  NodeDisplacements position = converged;
  for (const auto& [node, value] : prescribed_) {
    const Eigen::Vector3d e = direction(node);
    Eigen::Vector3d& u = position.try_emplace(node, Eigen::Vector3d::Zero()).first->second;
    u += (value - u.dot(e)) * e;
  }
  loads_.move_faces(position);
}

void DisplacementDrive::write(std::ostream& out) const {
  out << "** The nodes under the other solver, driven by its wall position (cocopp)\n"
         "*BOUNDARY, OP=NEW\n";
  for (const auto& [node, value] : prescribed_)
    out << fmt::format("{}, {}, {}, {}\n", node, dof_, dof_, ccx_number(value));
  out << "** The deck's own boundary conditions again (OP=NEW removed them)\n";
  for (const auto& line : model_boundary_) out << line << "\n";
  out << "** The other solver's loads, none in a driven direction\n";
  loads_.write_nodal_forces(out, film_forces_, [&](std::int64_t node, int dof) {
    return dof == dof_ && prescribed_.count(node) != 0;
  });
}

double DisplacementDrive::weight_in(std::int64_t node, std::size_t face) const {
  const auto& geometry = loads_.geometry()[face];
  const auto at = std::find(geometry.nodes.begin(), geometry.nodes.end(), node);
  return geometry.weights[static_cast<Eigen::Index>(at - geometry.nodes.begin())];
}

double DisplacementDrive::share(std::int64_t node, std::size_t face) const {
  double total = 0.0;
  for (const auto f : faces_of_.at(node)) total += weight_in(node, f);
  return weight_in(node, face) / total;
}

double DisplacementDrive::film_stiffness(std::size_t face) const {
  const auto row = static_cast<Eigen::Index>(face);
  return std::max(0.0, 2.0 * inputs_.pressure[row] / inputs_.gap[row]);
}

std::vector<std::vector<std::int64_t>> DisplacementDrive::driven_lines() const {
  struct Place {
    std::array<double, 6> axis;  ///< the transform's points a and b (a node's copy of its card)
    double axial, radius;
    std::int64_t node;
  };
  std::vector<Place> places;
  std::vector<std::vector<std::int64_t>> lines;
  for (const auto& [node, value] : prescribed_) {
    const NodalTransform* transform = deck_.transform(node);
    if (transform == nullptr || transform->type != 'C') {
      lines.push_back({node});
      continue;
    }
    const Eigen::Vector3d axis = (transform->b - transform->a).normalized();
    const Eigen::Vector3d from = deck_.node(node) - transform->a;
    const double axial = from.dot(axis);
    const std::array<double, 6> points = {transform->a.x(), transform->a.y(), transform->a.z(),
                                          transform->b.x(), transform->b.y(), transform->b.z()};
    places.push_back({points, axial, (from - axial * axis).norm(), node});
  }
  std::sort(places.begin(), places.end(), [](const Place& x, const Place& y) {
    return std::tie(x.axis, x.axial, x.radius) < std::tie(y.axis, y.axial, y.radius);
  });
  // Round-off apart (the sector's nodes are rotated copies) is one circle.
  const auto same_circle = [](const Place& x, const Place& y) {
    const double tolerance = 1e-9 * (std::abs(x.axial) + x.radius);
    return x.axis == y.axis && std::abs(x.axial - y.axial) <= tolerance &&
           std::abs(x.radius - y.radius) <= tolerance;
  };
  for (std::size_t i = 0; i < places.size(); ++i) {
    if (i == 0 || !same_circle(places[i - 1], places[i])) lines.emplace_back();
    lines.back().push_back(places[i].node);
  }
  return lines;
}

std::map<std::int64_t, double> DisplacementDrive::moves_by_line(
    const std::map<std::int64_t, double>& imbalance) const {
  const auto lines = driven_lines();
  const auto count = static_cast<Eigen::Index>(lines.size());
  Eigen::VectorXd force = Eigen::VectorXd::Zero(count), weight = Eigen::VectorXd::Zero(count),
                  film = Eigen::VectorXd::Zero(count);
  for (Eigen::Index i = 0; i < count; ++i) {
    double stiffness = 0.0;
    for (const auto node : lines[static_cast<std::size_t>(i)]) {
      force[i] += imbalance.at(node);
      for (const auto f : faces_of_.at(node)) {
        weight[i] += weight_in(node, f);
        stiffness += weight_in(node, f) * film_stiffness(f);
      }
    }
    // A serendipity face's corner alone takes a negative share of a uniform traction: such a
    // node cannot move by its own imbalance (the faces' balance below can).
    if (!(weight[i] > 0.0)) return {};
    largest_imbalance_ = std::max(largest_imbalance_, std::abs(force[i] / weight[i]));
    // The film's stiffness over the line's faces, weighted as the traction is (a corner's
    // negative weight could take it below zero next to a steep pressure drop: not below).
    film[i] = std::max(0.0, stiffness / weight[i]);
  }
  // Each line alone (the drive's own step, to the last bit), or all together.
  const bool coupled = compliance_ || reynolds_film_ || !probed_film_file_.empty();
  const Eigen::VectorXd move =
      !coupled
          ? Eigen::VectorXd((force.array() / weight.array()) / (film.array() + surface_stiffness_))
          : line_moves(lines, force, weight,
                       !probed_film_file_.empty() ? probed_film_stiffness(lines, weight, film)
                       : reynolds_film_           ? reynolds_film_stiffness(lines)
                                        : Eigen::MatrixXd(weight.cwiseProduct(film).asDiagonal()));
  if (!log_file_.empty()) log_lines(lines, force, weight, film, move);
  std::map<std::int64_t, double> moves;
  for (Eigen::Index i = 0; i < count; ++i)
    for (const auto node : lines[static_cast<std::size_t>(i)]) moves[node] = move[i];
  return moves;
}

void DisplacementDrive::log_lines(const std::vector<std::vector<std::int64_t>>& lines,
                                  const Eigen::VectorXd& force, const Eigen::VectorXd& weight,
                                  const Eigen::VectorXd& film, const Eigen::VectorXd& move) const {
  std::ofstream out(log_file_, std::ios::app);
  out << fmt::format("# step {} iteration {}", log_step_, ++log_iteration_);
  if (reynolds_film_) out << fmt::format(" reynolds_misfit {:.3f}", reynolds_misfit_);
  out << "\n";
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const auto node = lines[i].front();
    const auto k = static_cast<Eigen::Index>(i);
    const NodalTransform* transform = deck_.transform(node);
    const double axial = transform != nullptr && transform->type == 'C' ? axial_position(node)
                                                                        : deck_.node(node).z();
    out << fmt::format("{} {:.9e} {:.9e} {:.9e} {:.9e} {:.9e} {:.9e}\n", node, axial,
                       prescribed_.at(node), force[k], weight[k], film[k], move[k]);
  }
  if (!out) throw std::runtime_error("cannot write the drive log " + log_file_.string());
}

Eigen::VectorXd DisplacementDrive::line_moves(const std::vector<std::vector<std::int64_t>>& lines,
                                              const Eigen::VectorXd& force,
                                              const Eigen::VectorXd& weight,
                                              const Eigen::MatrixXd& film) const {
  if (!compliance_) {
    Eigen::MatrixXd system = film;
    system.diagonal() += surface_stiffness_ * weight;
    return system.partialPivLu().solve(force);
  }
  // (K_film + C^-1) d = F  <=>  (I + C K_film) d = C F, C the driven lines' compliance (the
  // others loaded, as ccx has them): no inverse of C, and K_film = 0 stays well posed.
  std::vector<Eigen::Index> rows;
  for (const auto& line : lines) {
    rows.push_back(*compliance_->row_of(line.front()));
    for (const auto node : line)
      if (compliance_->row_of(node) != rows.back())
        throw DeckError(
            fmt::format("nodes {} and {} move as one line, but the surface compliance has them in "
                        "different lines",
                        line.front(), node));
  }
  const Eigen::MatrixXd compliance = compliance_scale_ * compliance_->block(rows);
  Eigen::MatrixXd system = compliance * film;
  system.diagonal().array() += 1.0;
  return system.partialPivLu().solve(compliance * force);
}

Eigen::MatrixXd DisplacementDrive::probed_film_stiffness(
    const std::vector<std::vector<std::int64_t>>& lines, const Eigen::VectorXd& weight,
    const Eigen::VectorXd& film) const {
  const ProbedFilm probed = ProbedFilm::read(probed_film_file_);
  if (probed.step() != log_step_)
    throw std::runtime_error(fmt::format(
        "film probe {} is of step {}, the drive is in step {}: the film probes every step "
        "(COCOPP_SENSITIVITY_PROBE='every MOVE FILE') before the structure's first iteration",
        probed_film_file_.string(), probed.step(), log_step_));
  Eigen::VectorXd axial(static_cast<Eigen::Index>(lines.size()));
  for (std::size_t i = 0; i < lines.size(); ++i)
    axial[static_cast<Eigen::Index>(i)] = axial_position(lines[i].front());
  return probed.stiffness(axial, weight, film);
}

double DisplacementDrive::axial_position(std::int64_t node) const {
  const NodalTransform* transform = deck_.transform(node);
  if (transform == nullptr || transform->type != 'C')
    throw DeckError(fmt::format(
        "node {} is driven but in no cylindrical *TRANSFORM: film_stiffness: reynolds takes "
        "the film along the transform's axis",
        node));
  return (deck_.node(node) - transform->a).dot((transform->b - transform->a).normalized());
}

Eigen::MatrixXd DisplacementDrive::reynolds_film_stiffness(
    const std::vector<std::vector<std::int64_t>>& lines) const {
  // The film: every face it covers at all, along the axis. Its pressure reaches ambient where
  // it ends, which is inside the end faces (partly covered, not driven): a chain of driven
  // faces alone would put ambient pressure under the bearing's full pressure.
  std::vector<FilmFace> faces;
  for (std::size_t f = 0; f < driven_face_.size(); ++f) {
    const auto row = static_cast<Eigen::Index>(f);
    if (!(inputs_.coverage[row] > 0.0) || !(inputs_.gap[row] > 0.0)) continue;
    FilmFace face{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                  f};
    for (const auto node : loads_.geometry()[f].nodes) {
      const double axial = axial_position(node);
      face.start = std::min(face.start, axial);
      face.end = std::max(face.end, axial);
    }
    faces.push_back(face);
  }
  std::sort(faces.begin(), faces.end(),
            [](const FilmFace& x, const FilmFace& y) { return x.start < y.start; });
  std::map<std::int64_t, Eigen::Index> line_of;
  for (std::size_t i = 0; i < lines.size(); ++i)
    for (const auto node : lines[i]) line_of[node] = static_cast<Eigen::Index>(i);
  const auto count = static_cast<Eigen::Index>(lines.size());
  Eigen::MatrixXd stiffness = Eigen::MatrixXd::Zero(count, count);
  reynolds_misfit_ = 0.0;
  // Runs of faces that touch along the axis: one film each.
  std::size_t first = 0;
  while (first < faces.size()) {
    std::size_t last = first + 1;
    const double tolerance = 1e-6 * (faces[first].end - faces[first].start);
    while (last < faces.size() && faces[last].start <= faces[last - 1].end + tolerance) ++last;
    const std::vector<FilmFace> run(faces.begin() + static_cast<std::ptrdiff_t>(first),
                                    faces.begin() + static_cast<std::ptrdiff_t>(last));
    first = last;
    if (run.size() < 2) continue;  // a face alone: no film to speak of
    stiffness += film_run_stiffness(run, line_of, count);
  }
  return stiffness;
}

Eigen::MatrixXd DisplacementDrive::film_run_stiffness(
    const std::vector<FilmFace>& run, const std::map<std::int64_t, Eigen::Index>& line_of,
    Eigen::Index lines) const {
  const auto n = static_cast<Eigen::Index>(run.size());
  Eigen::VectorXd position(n), length(n), gap(n), pressure(n), inverse_area(n);
  Eigen::MatrixXd weight = Eigen::MatrixXd::Zero(n, lines);  // face x line
  for (Eigen::Index k = 0; k < n; ++k) {
    const FilmFace& face = run[static_cast<std::size_t>(k)];
    const auto row = static_cast<Eigen::Index>(face.index);
    // The mapped values are means over the whole face, zero where the film is not: the film's
    // own are those over the covered part, which lies towards the run's inside.
    const double covered = std::min(1.0, inputs_.coverage[row]);
    double start = face.start, end = face.end;
    if (k == 0) start = end - covered * (end - start);
    if (k == n - 1) end = start + covered * (end - start);
    position[k] = 0.5 * (start + end);
    length[k] = end - start;
    gap[k] = inputs_.gap[row] / covered;
    pressure[k] = inputs_.pressure[row] / covered;
    const auto& geometry = loads_.geometry()[face.index];
    inverse_area[k] = 1.0 / (covered * geometry.area);
    for (std::size_t m = 0; m < geometry.nodes.size(); ++m) {
      const auto line = line_of.find(geometry.nodes[m]);
      if (line != line_of.end())
        weight(k, line->second) += geometry.weights[static_cast<Eigen::Index>(m)];
    }
  }
  const ReynoldsFilm film(position, length, gap, pressure);
  reynolds_misfit_ = std::max(reynolds_misfit_, film.misfit());
  // A line's move d changes face g's mean gap by -weight(g, line) d / area_g, and a face's
  // pressure change dp_f pushes line i by -weight(f, i) dp_f: K = -W^T (dp/dh) diag(1/A) W.
  return -weight.transpose() * film.pressure_gradient() * inverse_area.asDiagonal() * weight;
}

std::map<std::int64_t, double> DisplacementDrive::moves_by_face(
    const std::map<std::int64_t, double>& imbalance) const {
  // Per driven face, the traction whose nodal forces a face's driven nodes share: each node's
  // imbalance split among its faces as a uniform traction's nodal force is, over the weight of
  // the face's driven nodes (its area when all are driven; undriven nodes carry the film's
  // load and have none). Exact for a uniform traction, and blind to a pattern whose shares
  // cancel on every face (a reduced-integration element's hoop zigzag, which a least-squares
  // fit to the consistent nodal forces would take for a traction).
  std::map<std::size_t, double> face_move;
  for (std::size_t f = 0; f < driven_face_.size(); ++f) {
    if (!driven_face_[f]) continue;
    const auto& face = loads_.geometry()[f];
    double force = 0.0, weight = 0.0;
    for (std::size_t i = 0; i < face.nodes.size(); ++i) {
      const auto at = imbalance.find(face.nodes[i]);
      if (at == imbalance.end()) continue;
      force += at->second * share(face.nodes[i], f);
      weight += face.weights[static_cast<Eigen::Index>(i)];
    }
    // Too little of the face driven to tell its traction (its corners alone, whose
    // serendipity weights are negative): it does not move.
    const double traction = weight > 0.1 * face.area ? force / weight : 0.0;
    face_move[f] = traction / (film_stiffness(f) + surface_stiffness_);
    largest_imbalance_ = std::max(largest_imbalance_, std::abs(traction));
  }
  // A driven node moves by its faces' moves, weighted by its shares in them.
  std::map<std::int64_t, double> moves;
  for (const auto& [node, value] : prescribed_)
    for (const auto f : faces_of_.at(node))
      if (driven_face_[f]) moves[node] += share(node, f) * face_move.at(f);
  return moves;
}

RowMatrix DisplacementDrive::balance(const RowMatrix& displacement,
                                     const RowMatrix& reaction) const {
  std::map<std::int64_t, Eigen::Index> row_of, reaction_row_of;
  for (std::size_t i = 0; i < interface_nodes_.size(); ++i)
    row_of[interface_nodes_[i]] = static_cast<Eigen::Index>(i);
  for (std::size_t i = 0; i < drivable_nodes_.size(); ++i)
    reaction_row_of[drivable_nodes_[i]] = static_cast<Eigen::Index>(i);
  // The nodal imbalance along the driven direction: the other solver's force minus the force
  // the structure takes (its reaction). Elsewhere the structure takes what is applied.
  std::map<std::int64_t, double> imbalance;
  for (const auto& [node, value] : prescribed_) {
    const auto film = film_forces_.find(node);
    const double film_force = film == film_forces_.end() ? 0.0 : film->second.dot(direction(node));
    imbalance[node] = film_force - reaction(reaction_row_of.at(node), dof_ - 1);
  }
  // Each circle of driven nodes moves by its own imbalance: every node line along the body is
  // balanced, so the coupling's fixed point is the nodal balance the loaded body would have.
  // Moves per face balance only each face's resultant, and a pattern along the body that
  // leaves every resultant alone (corner lines against mid-side lines) would stay as the
  // coupling left it. Where a line cannot move by its own (see moves_by_line), per face.
  largest_imbalance_ = 0.0;
  std::map<std::int64_t, double> moves = moves_by_line(imbalance);
  if (moves.empty()) {
    largest_imbalance_ = 0.0;
    moves = moves_by_face(imbalance);
  }
  RowMatrix result = displacement;
  for (const auto& [node, value] : prescribed_) {
    const auto output = row_of.find(node);
    if (output == row_of.end()) continue;  // driven, but not returned
    const Eigen::Vector3d e = direction(node);
    const Eigen::Index row = output->second;
    result.row(row) +=
        (value + moves.at(node) - result.row(row).dot(e.transpose())) * e.transpose();
  }
  return result;
}

}  // namespace cocopp::calculix

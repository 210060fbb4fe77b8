// A film's sensitivity to its wall, by finite differences (docs/wire-drawing.md, "The film's
// own sensitivity"): at one step's first coupling iteration, cocoppPimpleFoam solves the step
// again with each hoop line of wall points moved radially by a small amount, and writes how
// every face's force changed. A diagnostic for models of the interface's Jacobian; it changes
// nothing the coupler sees (the step is solved once more at the coupler's input afterwards).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "solvers/openfoam/pimple_foam_solver.hpp"
#include "solvers/openfoam/step_start_state.hpp"

namespace cocopp::openfoam {

using namespace Foam;

SensitivityProbe SensitivityProbe::from_environment() {
  const char* text = std::getenv("COCOPP_SENSITIVITY_PROBE");
  SensitivityProbe probe;
  if (text == nullptr || *text == '\0') return probe;
  std::istringstream in(text);
  std::string step;
  in >> step >> probe.move >> probe.file;
  bool options_known = true;
  for (std::string option; in >> option;) {
    if (option == "warm" || option == "cold")
      probe.warm = option == "warm";
    else if (option.rfind("hat=", 0) == 0)
      probe.hat = std::atoi(option.c_str() + 4);
    else
      options_known = false;
  }
  try {
    probe.step = !options_known || probe.hat < 1 ? 0 : step == "every" ? -1 : std::stoi(step);
  } catch (const std::exception&) {
    probe.step = 0;
  }
  if (probe.step == 0 || probe.step < -1 || !(probe.move > 0.0) || probe.file.empty())
    throw std::runtime_error(
        std::string("COCOPP_SENSITIVITY_PROBE='") + text +
        "': give 'STEP MOVE FILE [cold|warm] [hat=K]', e.g. '66 1e-8 probe.txt' "
        "(the step or 'every', the radial move in m, the file to write; "
        "warm: each probe starts from the step's solution; hat=K: every "
        "K-th line probed, its neighbours moved linearly less)");
  return probe;
}

namespace {

/// The radial unit vector of a point of a wedge about the z axis.
vector radial(const point& x) {
  const scalar r = std::hypot(x.x(), x.y());
  return vector(x.x() / r, x.y() / r, 0.0);
}

/// Each line's share of probe `at`'s move: 1 at its line, falling linearly to 0 at the probed
/// lines beside it (a hat function).
std::vector<double> hat_shares(const std::vector<std::size_t>& probed, std::size_t at,
                               std::size_t lines) {
  std::vector<double> share(lines, 0.0);
  const std::size_t centre = probed[at];
  share[centre] = 1.0;
  if (at > 0)
    for (std::size_t i = probed[at - 1] + 1; i < centre; ++i)
      share[i] = 1.0 - double(centre - i) / double(centre - probed[at - 1]);
  if (at + 1 < probed.size())
    for (std::size_t i = centre + 1; i < probed[at + 1]; ++i)
      share[i] = 1.0 - double(i - centre) / double(probed[at + 1] - centre);
  return share;
}

}  // namespace

void PimpleFoamSolver::probe_sensitivity(const std::vector<double>& input,
                                         const std::vector<double>& output) {
  if (Pstream::parRun() || patch_ids_.size() != 1 || gap_patch_id_ < 0)
    FatalErrorInFunction << "COCOPP_SENSITIVITY_PROBE needs a serial run with one interface "
                            "patch and a gap patch (a film)"
                         << exit(FatalError);
  const std::vector<label>& points = numbering_[0].point_ids();
  const std::vector<label>& faces = numbering_[0].face_ids();
  const pointField& points0 = initial_points();
  // A hoop line: the wall points at one axial position (both sides of the wedge).
  std::map<long long, std::vector<std::size_t>> by_position;
  for (std::size_t k = 0; k < points.size(); ++k)
    by_position[std::llround(points0[points[k]].z() / 1e-12)].push_back(k);
  std::vector<std::vector<std::size_t>> lines;
  for (auto& entry : by_position) lines.push_back(std::move(entry.second));
  // Probed: every hat-th line (and the last), moving the lines within hat of it by the hat
  // function's share, so that the answers interpolate linearly between the probed lines.
  const auto hat = static_cast<std::size_t>(probe_.hat);
  std::vector<std::size_t> probed;
  for (std::size_t i = 0; i < lines.size(); i += hat) probed.push_back(i);
  if (probed.back() != lines.size() - 1) probed.push_back(lines.size() - 1);
  // loads(): the points' wall displacement, then per face pressure, traction (3), gap, force.
  const std::size_t gap_at = 3 * points.size() + 4 * faces.size();
  const std::size_t force_at = gap_at + faces.size();
  const labelList face_labels(faces.begin(), faces.end());
  const vectorField centres(mesh_->faceCentres(), face_labels);
  const scalarField areas(mag(vectorField(mesh_->faceAreas(), face_labels)));
  const auto face_forces = [&](const std::vector<double>& values, std::size_t f) {
    const vector force(values[force_at + 3 * f], values[force_at + 3 * f + 1],
                       values[force_at + 3 * f + 2]);
    return std::make_pair(force & radial(centres[f]), force.z());
  };
  // Written beside and renamed when complete: a reader sees the last step's file or this one.
  const std::string partial = probe_.file + ".partial";
  std::ofstream file(partial);
  file << "# cocoppPimpleFoam sensitivity probe: step " << step_ << ", each hoop line of wall "
       << "points moved radially by " << probe_.move << " m (hat " << hat << ")\n# faces "
       << faces.size()
       << ": axial and radial position of the centre (m), area (m^2), gap (m), radial and axial "
          "force (N)\n";
  file.precision(10);
  // Warm: each probe's flow starts from this input's solution (on the step's start mesh, as
  // warm coupling iterations do), which a small move changes little.
  FlowFields solution;
  if (probe_.warm) solution.store(*mesh_);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto [radial_force, axial_force] = face_forces(output, f);
    file << centres[f].z() << ' ' << mag(centres[f] - centres[f].z() * vector(0, 0, 1)) << ' '
         << areas[f] << ' ' << output[gap_at + f] << ' ' << radial_force << ' ' << axial_force
         << '\n';
  }
  file << "# lines " << probed.size() << ": axial position (m), then per face the change of "
       << "its radial force, then of its axial force (N per m of move)\n";
  for (std::size_t at = 0; at < probed.size(); ++at) {
    const auto& members = lines[probed[at]];
    std::vector<double> moved = input;
    const std::vector<double> share = hat_shares(probed, at, lines.size());
    for (std::size_t i = 0; i < lines.size(); ++i)
      for (std::size_t k : lines[i]) {
        const vector outward = radial(points0[points[k]]);
        for (direction d = 0; d < 3; ++d) moved[3 * k + d] += share[i] * probe_.move * outward[d];
      }
    restore_step_start();
    if (probe_.warm) solution.restore(*mesh_);
    set_interface_displacement(moved);
    solve_pimple();
    const std::vector<double> answer = loads();
    file << points0[points[members.front()]].z();
    std::ostringstream axial;
    axial.precision(10);
    for (std::size_t f = 0; f < faces.size(); ++f) {
      const auto [r0, a0] = face_forces(output, f);
      const auto [r1, a1] = face_forces(answer, f);
      file << ' ' << (r1 - r0) / probe_.move;
      axial << ' ' << (a1 - a0) / probe_.move;
    }
    file << axial.str() << '\n';
    Info << "cocopp sensitivity probe: line at z = " << points0[points[members.front()]].z()
         << " m done" << nl << endl;
  }
  file.close();
  if (!file || std::rename(partial.c_str(), probe_.file.c_str()) != 0)
    FatalErrorInFunction << "cannot write the sensitivity probe " << probe_.file
                         << exit(FatalError);
  // The step as the coupler's input leaves it, for the next iteration's warm start.
  restore_step_start();
  if (probe_.warm) solution.restore(*mesh_);
  set_interface_displacement(input);
  solve_pimple();
}

}  // namespace cocopp::openfoam

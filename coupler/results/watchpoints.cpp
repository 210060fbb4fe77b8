#include "coupler/results/watchpoints.hpp"

#include <fmt/format.h>

#include <limits>
#include <set>
#include <stdexcept>

#include "core/case/suggest.hpp"

namespace cocopp {

namespace {

std::unique_ptr<Interpolator> create_interpolator(const Settings& item) {
  if (item.has("interpolator"))
    return InterpolatorRegistry::instance().create(item.child("interpolator"));
  static const Settings nearest = Settings::load_string("type: nearest", "<watchpoint default>");
  return InterpolatorRegistry::instance().create(nearest);
}

const Interface::Part* find_part(const Interface& interface, const std::string& name) {
  for (const auto& part : interface.parts())
    if (part.model_part->name == name) return &part;
  return nullptr;
}

std::string format_point(const Eigen::RowVector3d& p) {
  return fmt::format("({:g}, {:g}, {:g})", p.x(), p.y(), p.z());
}

}  // namespace

Watchpoints::Watchpoints(const Settings& settings) {
  if (!settings.has("watchpoints")) return;
  std::set<std::string> names;
  for (const Settings& item : settings.list("watchpoints")) {
    Definition d;
    d.name = item.get_name("name", "");
    if (d.name.empty()) item.fail("name", "a watchpoint needs a name (a plain name)");
    if (!names.insert(d.name).second)
      item.fail("name", "two watchpoints are called '" + d.name + "': give them different names");
    const auto point = item.required<std::vector<double>>("coordinates");
    if (point.size() != 3)
      item.fail("coordinates",
                fmt::format("give three coordinates [x, y, z] in m, not {}", point.size()));
    d.point = Eigen::RowVector3d(point[0], point[1], point[2]);
    d.model_part = item.get<std::string>("model_part", "");
    d.where = item.where("name") + ": watchpoint '" + d.name + "'";
    d.on_x = create_interpolator(item);
    d.on_y = create_interpolator(item);
    definitions_.push_back(std::move(d));
  }
}

std::string Watchpoints::nearest_model_part(const Definition& d, const Interface& x,
                                            const Interface& y) const {
  std::string nearest;
  double best = std::numeric_limits<double>::infinity();
  for (const Interface* interface : {&x, &y})
    for (const auto& part : interface->parts()) {
      const Coordinates& points = part.model_part->coordinates;
      if (points.rows() == 0) continue;
      const double distance = (points.rowwise() - d.point).rowwise().squaredNorm().minCoeff();
      if (distance < best) best = distance, nearest = part.model_part->name;
    }
  if (nearest.empty()) throw std::runtime_error(d.where + ": the interfaces have no points");
  return nearest;
}

void Watchpoints::build(Definition& d, Interpolator& interpolator, const ModelPart& part) const {
  Coordinates target(1, 3);
  target.row(0) = d.point;
  try {
    interpolator.initialize(part.coordinates, target);
  } catch (const std::exception& e) {
    const double distance =
        std::sqrt((part.coordinates.rowwise() - d.point).rowwise().squaredNorm().minCoeff());
    throw std::runtime_error(fmt::format(
        "{} at {} on model part '{}' ({} points; the nearest is {:g} m away): {}. What to "
        "change: a point on the interface (its initial coordinates), or an interpolator that "
        "reaches it, e.g. `interpolator: {{type: nearest, max_distance: {:g}}}`",
        d.where, format_point(d.point), part.name, part.size(), distance, e.what(), 2 * distance));
  }
}

void Watchpoints::attach(const Interface& x, const Interface& y) {
  std::vector<Interface::Part> parts;
  sources_.clear();
  for (std::size_t index = 0; index < definitions_.size(); ++index) {
    Definition& d = definitions_[index];
    if (d.model_part.empty()) d.model_part = nearest_model_part(d, x, y);
    const Interface::Part* on_x = find_part(x, d.model_part);
    const Interface::Part* on_y = find_part(y, d.model_part);
    if (!on_x && !on_y) {
      std::vector<std::string> names;
      for (const Interface* interface : {&x, &y})
        for (const auto& part : interface->parts())
          if (std::find(names.begin(), names.end(), part.model_part->name) == names.end())
            names.push_back(part.model_part->name);
      throw std::runtime_error(
          fmt::format("{}: no model part '{}' on the interfaces (they have {}){}", d.where,
                      d.model_part, fmt::join(names, ", "), did_you_mean(d.model_part, names)));
    }
    auto watched = std::make_shared<ModelPart>();
    watched->name = d.name;
    watched->ids = {0};
    watched->coordinates = Coordinates(1, 3);
    watched->coordinates.row(0) = d.point;
    std::vector<std::string> variables;
    if (on_x) {
      build(d, *d.on_x, *on_x->model_part);
      for (const auto& variable : on_x->variables) {
        variables.push_back(variable);
        sources_.push_back({index, variable, true});
      }
    }
    if (on_y) {
      build(d, *d.on_y, *on_y->model_part);
      for (const auto& variable : on_y->variables)
        if (std::find(variables.begin(), variables.end(), variable) == variables.end()) {
          variables.push_back(variable);
          sources_.push_back({index, variable, false});
        }
    }
    parts.push_back({watched, variables});
  }
  values_ = Interface(std::move(parts));
}

const Interface& Watchpoints::sample(const Interface& x, const Interface& y) {
  for (const Source& source : sources_) {
    const Definition& d = definitions_[source.definition];
    const Interpolator& interpolator = source.from_x ? *d.on_x : *d.on_y;
    values_.values(d.name, source.variable) =
        interpolator.map((source.from_x ? x : y).values(d.model_part, source.variable));
  }
  return values_;
}

std::vector<std::string> Watchpoints::source_parts() const {
  std::vector<std::string> parts;
  for (const auto& d : definitions_) parts.push_back(d.model_part);
  return parts;
}

}  // namespace cocopp

#pragma once
// Run-time selection by name: every component kind (coupled solver, model, predictor,
// convergence criterion, solver wrapper, interpolator, transformer) has a registry; a component
// registers itself with one COCOPP_REGISTER line in its own source file, named after its type,
// and is created from the `type` key of its settings. A name registered twice stops the program
// at start-up with both places named: a registry never silently keeps one of two.
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/case/settings.hpp"
#include "core/case/suggest.hpp"

namespace cocopp {

template <class Base, class... Args>
class Registry {
 public:
  using Factory = std::function<std::unique_ptr<Base>(const Settings&, Args...)>;

  static Registry& instance() {
    static Registry registry;
    return registry;
  }

  /// Register `factory` under `name`; `origin` (the source file) names it in errors. A name
  /// that is taken already throws std::logic_error naming both origins.
  bool add(const std::string& name, const std::string& origin, Factory factory) {
    const auto [entry, inserted] = factories_.try_emplace(name, Entry{origin, std::move(factory)});
    if (!inserted)
      throw std::logic_error(std::string(Base::kind) + " '" + name + "' is registered twice: in " +
                             entry->second.origin + " and in " + origin);
    return true;
  }

  /// add() for static initializers, where an exception cannot be caught: a duplicate prints the
  /// error and aborts before main().
  bool add_at_start_up(const std::string& name, const std::string& origin, Factory factory) {
    try {
      return add(name, origin, std::move(factory));
    } catch (const std::logic_error& error) {
      std::fprintf(stderr, "cocopp: internal error: %s\n", error.what());
      std::abort();
    }
  }

  /// Where `name` was registered (empty if it is not).
  std::string origin(const std::string& name) const {
    const auto found = factories_.find(name);
    return found == factories_.end() ? std::string() : found->second.origin;
  }

  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& entry : factories_) out.push_back(entry.first);
    return out;
  }

  /// Create the component registered as `name` (one of names()): for kinds that are not
  /// chosen by a `type` key but each asked for by keys of their own (the run's outputs).
  std::unique_ptr<Base> create_named(const std::string& name, const Settings& settings,
                                     Args... args) const {
    return factories_.at(name).factory(settings, std::forward<Args>(args)...);
  }

  /// Create the component named by settings' `type`; unknown names are case errors.
  std::unique_ptr<Base> create(const Settings& settings, Args... args) const {
    const auto type = settings.template required<std::string>("type");
    const auto found = factories_.find(type);
    if (found == factories_.end())
      settings.fail("type", "unknown " + std::string(Base::kind) + " '" + type + "'" +
                                did_you_mean(type, names()) + " (available: " + join(names()) +
                                ")");
    return found->second.factory(settings, std::forward<Args>(args)...);
  }

 private:
  struct Entry {
    std::string origin;
    Factory factory;
  };
  std::map<std::string, Entry> factories_;
};

}  // namespace cocopp

#define COCOPP_CONCAT_INNER(a, b) a##b
#define COCOPP_CONCAT(a, b) COCOPP_CONCAT_INNER(a, b)

/// Register `Class` (constructible from (const Settings&, Args...)) under `name` in the
/// registry of `RegistryType`, e.g. COCOPP_REGISTER(PredictorRegistry, "linear", Linear).
#define COCOPP_REGISTER(RegistryType, name, Class)                                            \
  namespace {                                                                                 \
  const bool COCOPP_CONCAT(cocopp_registered_, __LINE__) =                                    \
      RegistryType::instance().add_at_start_up(name, __FILE__,                                \
                                               [](const ::cocopp::Settings& s, auto&&... a) { \
                                                 return std::make_unique<Class>(              \
                                                     s, std::forward<decltype(a)>(a)...);     \
                                               });                                            \
  }

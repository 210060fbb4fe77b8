#pragma once
// Run-time selection by name: every component kind (coupled solver, model, predictor,
// convergence criterion, solver wrapper) has a registry; a component registers itself with one
// COCOPP_REGISTER line in its own source file and is created from the `type` key of its settings.
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "coupler/case/settings.hpp"
#include "coupler/case/suggest.hpp"

namespace cocopp {

template <class Base, class... Args>
class Registry {
 public:
  using Factory = std::function<std::unique_ptr<Base>(const Settings&, Args...)>;

  static Registry& instance() {
    static Registry registry;
    return registry;
  }

  bool add(const std::string& name, Factory factory) {
    factories_[name] = std::move(factory);
    return true;
  }

  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& entry : factories_) out.push_back(entry.first);
    return out;
  }

  /// Create the component named by settings' `type`; unknown names are case errors.
  std::unique_ptr<Base> create(const Settings& settings, Args... args) const {
    const auto type = settings.template required<std::string>("type");
    const auto found = factories_.find(type);
    if (found == factories_.end())
      settings.fail("type", "unknown " + std::string(Base::kind) + " '" + type + "'" +
                                did_you_mean(type, names()) + " (available: " + join(names()) +
                                ")");
    return found->second(settings, std::forward<Args>(args)...);
  }

 private:
  std::map<std::string, Factory> factories_;
};

}  // namespace cocopp

#define COCOPP_CONCAT_INNER(a, b) a##b
#define COCOPP_CONCAT(a, b) COCOPP_CONCAT_INNER(a, b)

/// Register `Class` (constructible from (const Settings&, Args...)) under `name` in the
/// registry of `RegistryType`, e.g. COCOPP_REGISTER(PredictorRegistry, "linear", Linear).
#define COCOPP_REGISTER(RegistryType, name, Class)                                      \
  namespace {                                                                           \
  const bool COCOPP_CONCAT(cocopp_registered_, __LINE__) =                              \
      RegistryType::instance().add(name, [](const ::cocopp::Settings& s, auto&&... a) { \
        return std::make_unique<Class>(s, std::forward<decltype(a)>(a)...);             \
      });                                                                               \
  }

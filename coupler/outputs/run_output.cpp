#include "coupler/outputs/run_output.hpp"

namespace cocopp {

std::vector<std::unique_ptr<RunOutput>> create_outputs(const Settings& settings) {
  const auto& registry = RunOutputRegistry::instance();
  std::vector<std::unique_ptr<RunOutput>> outputs;
  for (const auto& name : registry.names()) {
    auto output = registry.create_named(name, settings);
    if (output->active()) outputs.push_back(std::move(output));
  }
  return outputs;
}

}  // namespace cocopp

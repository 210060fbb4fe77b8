// Fuzz target: reading ccx's .dat file (the displacements *NODE PRINT wrote for the interface
// node set), as the calculix wrapper does after every ccx run.
#include <cstdint>
#include <exception>

#include "solver_wrappers/calculix/dat_file.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = cocopp::fuzz::write_input("job.dat", data, size);
  try {
    (void)cocopp::calculix::read_node_print(file, "displacements", "WALLMID", {1, 2, 3});
  } catch (const std::exception&) {
    // a clean error
  }
  return 0;
}

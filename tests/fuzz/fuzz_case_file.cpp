// Fuzz target: case files (YAML and JSON) through everything `cocopp check` does before it
// looks at the solvers' own files: the parser, every component's reading of its keys, and the
// unknown-key check. Any std::exception is a clean error (the app prints it with the file and
// line); a crash, a sanitizer report, a hang or a huge allocation is a finding.
#include <cstdint>
#include <exception>

#include "coupler/app/case.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = cocopp::fuzz::write_input("case.yaml", data, size);
  try {
    (void)cocopp::load_case(file);
  } catch (const std::exception&) {
    // a clean error
  }
  return 0;
}

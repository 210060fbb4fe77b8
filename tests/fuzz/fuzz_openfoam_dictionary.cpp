// Fuzz target: the OpenFOAM dictionary reader the openfoam wrapper checks a case with
// (controlDict, dynamicMeshDict, transportProperties, decomposeParDict) and the reader of a
// mesh's constant/polyMesh/boundary file.
#include <cstdint>
#include <exception>

#include "solver_wrappers/openfoam/openfoam_case.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using cocopp::openfoam::FoamDictionary;
  const auto file = cocopp::fuzz::write_input("controlDict", data, size);
  try {
    const FoamDictionary dictionary = FoamDictionary::read(file);
    for (const char* keyword : {"application", "deltaT", "dynamicFvMesh", "nu"})
      if (dictionary.has(keyword)) {
        (void)dictionary.value(keyword);
        (void)dictionary.where(keyword);
      }
    (void)dictionary.number("deltaT");
  } catch (const std::exception&) {
    // a clean error
  }
  try {
    (void)cocopp::openfoam::read_boundary_patches(file);
  } catch (const std::exception&) {
  }
  return 0;
}

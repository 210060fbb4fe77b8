// Fuzz target: the CalculiX input deck reader (.inp, the user's deck the calculix wrapper reads)
// and what the wrapper builds from it: the faces of surface WALL with their geometry and
// nodal loads, the node set WALLMID (the names of examples/tube/flow_calculix, whose decks
// seed the corpus). DeckError, and std::exception in general, is a clean error.
#include <cstdint>
#include <exception>

#include "solver_wrappers/calculix/input_deck.hpp"
#include "solver_wrappers/calculix/interface_loads.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace cocopp::calculix;
  const auto file = cocopp::fuzz::write_input("deck.inp", data, size);
  try {
    const InputDeck deck = InputDeck::read(file, file.parent_path());
    (void)deck.node_set("WALLMID");
    const InterfaceLoads loads(deck, deck.surface("WALL"));
    cocopp::RowMatrix traction(static_cast<Eigen::Index>(loads.faces().size()), 3);
    traction.setOnes();
    (void)loads.nodal_forces(traction);
  } catch (const std::exception&) {
    // a clean error
  }
  return 0;
}

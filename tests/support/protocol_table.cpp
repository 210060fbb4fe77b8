// cocopp-protocol-table: the protocol's constants and the variable table as the C++ side
// defines them, as JSON, for the tests that hold the Python SDK and docs/protocol.md to them
// (tests/unit/core/protocol/test_protocol_tables.py).
#include <iostream>
#include <nlohmann/json.hpp>

#include "core/protocol/frame.hpp"
#include "core/protocol/messages.hpp"
#include "core/protocol/variable_components.hpp"

int main() {
  using namespace cocopp::protocol;
  nlohmann::ordered_json table;
  table["protocol_version"] = kProtocolVersion;
  table["max_payload"] = kMaxPayloadBytes;
  for (int byte = 0; byte < 256; ++byte) {
    // Every known type has a name; unknown ones say so.
    const std::string name = message_name(static_cast<MessageType>(byte));
    if (name.rfind("unknown", 0) != 0) table["message_types"][name] = byte;
  }
  for (const auto& variable : variable_definitions())
    table["variables"][variable.name] = {{"components", variable.components},
                                         {"unit", variable.unit}};
  std::cout << table.dump(2) << "\n";
}

// The component registry: creation by `type`, errors for unknown and missing types, and a name
// registered twice, which must never pass silently.
#include <gtest/gtest.h>

#include "core/case/registry.hpp"
#include "core/case/settings.hpp"

using namespace cocopp;

namespace {

struct Gadget {
  static constexpr const char* kind = "gadget";
  explicit Gadget(std::string n) : name(std::move(n)) {}
  virtual ~Gadget() = default;
  std::string name;
};

struct Lever : Gadget {
  explicit Lever(const Settings&) : Gadget("lever") {}
};
struct Wheel : Gadget {
  explicit Wheel(const Settings&) : Gadget("wheel") {}
};

/// A registry of its own per test (the singletons are the production registries).
Registry<Gadget> gadgets() {
  Registry<Gadget> registry;
  registry.add("lever", "lever.cpp", [](const Settings& s) { return std::make_unique<Lever>(s); });
  registry.add("wheel", "wheel.cpp", [](const Settings& s) { return std::make_unique<Wheel>(s); });
  return registry;
}

std::string create_error(const Registry<Gadget>& registry, const std::string& yaml) {
  const Settings s = Settings::load_string(yaml, "case.yaml");
  try {
    registry.create(s.child("gadget"));
  } catch (const CaseError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(Registry, CreatesByTypeAndKnowsWhere) {
  const auto registry = gadgets();
  const Settings s = Settings::load_string("gadget:\n  type: wheel\n", "case.yaml");
  EXPECT_EQ(registry.create(s.child("gadget"))->name, "wheel");
  EXPECT_EQ(registry.names(), (std::vector<std::string>{"lever", "wheel"}));
  EXPECT_EQ(registry.origin("lever"), "lever.cpp");
  EXPECT_EQ(registry.origin("crank"), "");
}

TEST(Registry, UnknownTypeSuggestsAndLists) {
  const std::string message = create_error(gadgets(), "gadget:\n  type: wheal\n");
  EXPECT_NE(message.find("case.yaml:2:"), std::string::npos) << message;
  EXPECT_NE(message.find("unknown gadget 'wheal'; did you mean 'wheel'?"), std::string::npos)
      << message;
  EXPECT_NE(message.find("available: lever, wheel"), std::string::npos) << message;
}

TEST(Registry, MissingTypeIsAnError) {
  const std::string message = create_error(gadgets(), "gadget:\n  size: 2\n");
  EXPECT_NE(message.find("type"), std::string::npos) << message;
}

TEST(Registry, NameRegisteredTwiceNamesBothPlaces) {
  auto registry = gadgets();
  try {
    registry.add("wheel", "other_wheel.cpp",
                 [](const Settings& s) { return std::make_unique<Lever>(s); });
    FAIL() << "no error";
  } catch (const std::logic_error& e) {
    EXPECT_STREQ(e.what(),
                 "gadget 'wheel' is registered twice: in wheel.cpp and in other_wheel.cpp");
  }
  // The first registration stays.
  const Settings s = Settings::load_string("gadget:\n  type: wheel\n", "case.yaml");
  EXPECT_EQ(registry.create(s.child("gadget"))->name, "wheel");
}

TEST(RegistryDeathTest, DuplicateAtStartUpStopsTheProgram) {
  auto registry = gadgets();
  EXPECT_DEATH(
      registry.add_at_start_up("lever", "second_lever.cpp",
                               [](const Settings& s) { return std::make_unique<Lever>(s); }),
      "internal error: gadget 'lever' is registered twice: in lever.cpp and in "
      "second_lever.cpp");
}

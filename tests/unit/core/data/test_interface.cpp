// Interface: model parts x variables flattened into one vector in the documented layout (the
// protocol sends exactly this vector), views of one block, layout comparison, and errors that
// say what is there.
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>

#include "core/data/interface.hpp"
#include "tests/support/error_message.hpp"

namespace cocopp {
namespace {

using cocopp::testing::error_message;

std::shared_ptr<ModelPart> part(const std::string& name, int points) {
  auto model_part = std::make_shared<ModelPart>();
  model_part->name = name;
  model_part->coordinates = Coordinates::Zero(points, 3);
  for (int i = 0; i < points; ++i) model_part->ids.push_back(10 + i);
  return model_part;
}

TEST(Interface, DataIsPartByPartVariableByVariablePointByPointComponentsContiguous) {
  Interface interface({{part("wall", 2), {"pressure", "traction"}}, {part("tip", 1), {"force"}}});
  ASSERT_EQ(interface.size(), 2 * 1 + 2 * 3 + 1 * 3);
  const auto& blocks = interface.blocks();
  ASSERT_EQ(blocks.size(), 3u);
  EXPECT_EQ(blocks[1].model_part, "wall");
  EXPECT_EQ(blocks[1].variable, "traction");
  EXPECT_EQ(blocks[1].offset, 2);
  EXPECT_EQ(blocks[1].points, 2);
  EXPECT_EQ(blocks[1].components, 3);
  EXPECT_EQ(blocks[2].offset, 8);

  Eigen::VectorXd values = Eigen::VectorXd::LinSpaced(interface.size(), 0.0, 10.0);
  interface.set_data(values);
  // Point 1's traction: row 1 of the block, components 5, 6, 7 of the vector.
  const auto traction = interface.values("wall", "traction");
  EXPECT_EQ(traction.rows(), 2);
  EXPECT_EQ(traction(1, 0), values[5]);
  EXPECT_EQ(traction(1, 2), values[7]);
  // A view writes through.
  interface.values("tip", "force")(0, 1) = -1.0;
  EXPECT_EQ(interface.data()[9], -1.0);
  EXPECT_EQ(interface.describe(),
            "wall: pressure (2 x 1); wall: traction (2 x 3); tip: force (1 x 3)");
}

TEST(Interface, SameLayoutComparesPartsPointsAndVariablesInOrder) {
  const Interface a({{part("wall", 2), {"pressure", "traction"}}});
  EXPECT_TRUE(a.same_layout(Interface({{part("wall", 2), {"pressure", "traction"}}})));
  EXPECT_FALSE(a.same_layout(Interface({{part("wall", 2), {"traction", "pressure"}}})));
  EXPECT_FALSE(a.same_layout(Interface({{part("wall", 3), {"pressure", "traction"}}})));
  EXPECT_FALSE(a.same_layout(Interface({{part("side", 2), {"pressure", "traction"}}})));
  EXPECT_FALSE(a.same_layout(Interface({{part("wall", 2), {"pressure"}}})));
  EXPECT_EQ(Interface().describe(), "empty");
}

TEST(Interface, ErrorsSayWhatIsThere) {
  EXPECT_NE(error_message<std::invalid_argument>([] {
              Interface({{part("wall", 1), {"presure"}}});
            }).find("unknown interface variable 'presure'; did you mean 'pressure'"),
            std::string::npos);
  EXPECT_NE(error_message<std::invalid_argument>([] {
              Interface({{part("wall", 1), {"pressure"}}, {part("wall", 2), {"force"}}});
            }).find("model part 'wall' appears twice"),
            std::string::npos);
  Interface interface({{part("wall", 2), {"pressure"}}});
  EXPECT_NE(error_message<std::invalid_argument>([&] {
              interface.set_data(Eigen::VectorXd::Zero(3));
            }).find("size 3 given where 2 values are expected (wall: pressure (2 x 1))"),
            std::string::npos);
  EXPECT_NE(error_message<std::out_of_range>([&] {
              (void)interface.values("wall", "traction");
            }).find("no variable 'traction' on model part 'wall' (it has: wall: pressure"),
            std::string::npos);
}

}  // namespace
}  // namespace cocopp

// Watchpoints (variables at points, from the case file) and WatchpointCsv, and the watchpoints
// group of the results file.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "coupler/results/watchpoint_csv.hpp"
#include "coupler/results/watchpoints.hpp"
#include "tests/support/error_message.hpp"
#include "tests/support/temporary_directory.hpp"
#include "tests/unit/coupler/results/results_fixture.hpp"

namespace cocopp {
namespace {

Settings settings_of(const std::string& yaml) {
  return Settings::load_string(yaml, "case.yaml").child("settings");
}

Watchpoints read(const std::string& watchpoints_yaml) {
  return Watchpoints(settings_of("settings:\n  watchpoints:\n" + watchpoints_yaml));
}

/// The fixture's interfaces ("wall": 4 points at z = 0, 0.01, 0.02, 0.03; "inlet": 2 at z =
/// -0.01, 0) with values linear in z: displacement (z, 2z, 3z), pressure 1000 z.
test::Interfaces linear_fields() {
  test::Interfaces interfaces = test::make_interfaces();
  for (const auto& part : interfaces.x.parts()) {
    const auto z = part.model_part->coordinates.col(2);
    auto values = interfaces.x.values(part.model_part->name, "displacement");
    values.col(0) = z;
    values.col(1) = 2 * z;
    values.col(2) = 3 * z;
    interfaces.y.values(part.model_part->name, "pressure") = 1000 * z;
  }
  interfaces.y.values("wall", "traction").setConstant(7.0);
  return interfaces;
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(Watchpoints, NoneWithoutTheKey) {
  EXPECT_TRUE(Watchpoints(settings_of("settings:\n  delta_t: 1\n")).empty());
}

TEST(Watchpoints, NearestTakesTheNearestPointsValuesOfXAndY) {
  auto watchpoints = read("    - {name: near, model_part: wall, coordinates: [0.005, 0, 0.011]}\n");
  auto fields = linear_fields();
  watchpoints.attach(fields.x, fields.y);
  const Interface& values = watchpoints.sample(fields.x, fields.y);
  // One model part of one point; x's variables, then y's.
  ASSERT_EQ(values.blocks().size(), 3u);
  EXPECT_EQ(values.blocks()[0].variable, "displacement");
  EXPECT_EQ(values.blocks()[1].variable, "pressure");
  EXPECT_EQ(values.blocks()[2].variable, "traction");
  EXPECT_DOUBLE_EQ(values.values("near", "displacement")(0, 1), 0.02);  // the point at z = 0.01
  EXPECT_DOUBLE_EQ(values.values("near", "pressure")(0, 0), 10.0);
  EXPECT_DOUBLE_EQ(values.values("near", "traction")(0, 2), 7.0);
  EXPECT_DOUBLE_EQ(values.parts()[0].model_part->coordinates(0, 2), 0.011);
}

TEST(Watchpoints, LinearInterpolatesALinearFieldExactly) {
  auto watchpoints = read(
      "    - name: between\n      model_part: wall\n      coordinates: [0.005, 0, 0.0137]\n"
      "      interpolator: {type: linear, directions: [z]}\n");
  auto fields = linear_fields();
  watchpoints.attach(fields.x, fields.y);
  const Interface& values = watchpoints.sample(fields.x, fields.y);
  EXPECT_NEAR(values.values("between", "displacement")(0, 2), 3 * 0.0137, 1e-15);
  EXPECT_NEAR(values.values("between", "pressure")(0, 0), 13.7, 1e-12);
  // The values follow the interfaces: sampled again after a change.
  fields.y.values("wall", "pressure").setConstant(-5.0);
  EXPECT_DOUBLE_EQ(watchpoints.sample(fields.x, fields.y).values("between", "pressure")(0, 0),
                   -5.0);
}

TEST(Watchpoints, WithoutAModelPartTheNearestPartIsTaken) {
  auto watchpoints = read("    - {name: entry, coordinates: [0.005, 0, -0.0099]}\n");
  auto fields = linear_fields();
  watchpoints.attach(fields.x, fields.y);
  EXPECT_EQ(watchpoints.source_parts(), std::vector<std::string>{"inlet"});
  EXPECT_DOUBLE_EQ(watchpoints.sample(fields.x, fields.y).values("entry", "pressure")(0, 0), -10.0);
}

TEST(Watchpoints, AnUnknownModelPartIsNamedWithWhereAndTheNearestName) {
  auto watchpoints = read("    - {name: w, model_part: wal, coordinates: [0.005, 0, 0]}\n");
  auto fields = linear_fields();
  const std::string message =
      testing::error_message<std::exception>([&] { watchpoints.attach(fields.x, fields.y); });
  EXPECT_NE(message.find("case.yaml:3:"), std::string::npos) << message;
  EXPECT_NE(message.find("watchpoint 'w': no model part 'wal' on the interfaces (they have "
                         "wall, inlet); did you mean 'wall'?"),
            std::string::npos)
      << message;
}

TEST(Watchpoints, APointOffTheInterfaceSaysHowFarAndWhatToChange) {
  auto watchpoints = read("    - {name: off, model_part: wall, coordinates: [0.105, 0, 0.01]}\n");
  auto fields = linear_fields();
  const std::string message =
      testing::error_message<std::exception>([&] { watchpoints.attach(fields.x, fields.y); });
  EXPECT_NE(message.find("watchpoint 'off' at (0.105, 0, 0.01) on model part 'wall' (4 points; "
                         "the nearest is 0.1 m away)"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("do not overlap"), std::string::npos) << message;
  EXPECT_NE(message.find("max_distance: 0.2"), std::string::npos) << message;
}

TEST(Watchpoints, BadDefinitionsFailAtTheirKey) {
  const auto fails_with = [](const std::string& yaml, const std::string& expected) {
    const std::string message = testing::error_message<std::exception>([&] { read(yaml); });
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  };
  fails_with("    - {name: a, coordinates: [0, 0]}\n", "give three coordinates");
  fails_with("    - {name: a, coordinates: [0, 0, 0]}\n    - {name: a, coordinates: [1, 0, 0]}\n",
             "two watchpoints are called 'a'");
  fails_with("    - {name: ../a, coordinates: [0, 0, 0]}\n", "name");
  fails_with("    - {name: a, coordinates: [0, 0, 0], interpolator: {type: linaer}}\n",
             "did you mean 'linear'?");
}

TEST(WatchpointCsv, OneFilePerWatchpointWithAHeaderAndARowPerStep) {
  testing::TemporaryDirectory directory;
  auto watchpoints = read(
      "    - {name: a, model_part: wall, coordinates: [0.005, 0, 0.01]}\n"
      "    - {name: b, model_part: inlet, coordinates: [0.005, 0, 0]}\n");
  auto fields = linear_fields();
  watchpoints.attach(fields.x, fields.y);
  WatchpointCsv csv(RunFiles{directory.path() / "results", "case"}, watchpoints.layout());
  ASSERT_EQ(csv.files().size(), 2u);
  EXPECT_EQ(csv.files()[0], directory.path() / "results" / "case_watchpoint_a.csv");
  csv.write_step(1, 0.01, watchpoints.sample(fields.x, fields.y));
  fields.y.values("wall", "pressure").setConstant(0.1);
  csv.write_step(2, 0.02, watchpoints.sample(fields.x, fields.y));
  EXPECT_EQ(read_file(csv.files()[0]),
            "step,time,displacement_x,displacement_y,displacement_z,pressure,traction_x,"
            "traction_y,traction_z\n"
            "1,0.01,0.01,0.02,0.03,10,7,7,7\n"
            "2,0.02,0.01,0.02,0.03,0.1,7,7,7\n");
  EXPECT_EQ(read_file(csv.files()[1]),
            "step,time,displacement_x,displacement_y,displacement_z,pressure\n"
            "1,0.01,0,0,0,0\n2,0.02,0,0,0,0\n");
}

TEST(WatchpointCsv, ARestartKeepsTheRowsUpToItsStep) {
  testing::TemporaryDirectory directory;
  auto watchpoints = read("    - {name: a, model_part: inlet, coordinates: [0.005, 0, 0]}\n");
  auto fields = linear_fields();
  watchpoints.attach(fields.x, fields.y);
  {
    WatchpointCsv csv(RunFiles{directory.path(), "case"}, watchpoints.layout());
    for (int step = 1; step <= 4; ++step)
      csv.write_step(step, 0.01 * step, watchpoints.sample(fields.x, fields.y));
  }
  WatchpointCsv continued(RunFiles{directory.path(), "case"}, watchpoints.layout(), 2);
  continued.write_step(3, 0.03, watchpoints.sample(fields.x, fields.y));
  EXPECT_EQ(read_file(continued.files()[0]),
            "step,time,displacement_x,displacement_y,displacement_z,pressure\n"
            "1,0.01,0,0,0,0\n2,0.02,0,0,0,0\n3,0.03,0,0,0,0\n");

  auto other = read("    - {name: a, model_part: wall, coordinates: [0.005, 0, 0]}\n");
  other.attach(fields.x, fields.y);
  const std::string message = testing::error_message<std::exception>([&] {
    WatchpointCsv(RunFiles{directory.path(), "case"}, other.layout(), 2);
  });
  EXPECT_NE(message.find("was the case changed?"), std::string::npos) << message;
}

TEST(ResultsWriter, KeepsTheWatchpointsLikeTheInterfaces) {
  testing::TemporaryDirectory directory;
  const auto file = directory.path() / "run.h5";
  auto watchpoints = read("    - {name: a, model_part: wall, coordinates: [0.005, 0, 0.02]}\n");
  auto fields = linear_fields();
  watchpoints.attach(fields.x, fields.y);
  {
    ResultsWriter writer(file, test::make_run(3), fields.x, fields.y, watchpoints.layout());
    for (int step = 1; step <= 3; ++step) {
      fields.y.values("wall", "pressure").setConstant(step);
      writer.write_step(test::make_record(step), fields.x, fields.y,
                        watchpoints.sample(fields.x, fields.y));
    }
    writer.close("completed", "");
  }
  {
    // A restart after step 2 drops step 3's row and continues.
    ResultsWriter writer(file, test::make_run(3), fields.x, fields.y, 2, watchpoints.layout());
    fields.y.values("wall", "pressure").setConstant(30.0);
    writer.write_step(test::make_record(3), fields.x, fields.y,
                      watchpoints.sample(fields.x, fields.y));
    writer.close("completed", "");
  }
  const ResultsReader reader(file);
  const auto pressure = reader.dataset("watchpoints/a/pressure");
  EXPECT_EQ(pressure.shape, (ResultsReader::Shape{3, 1, 1}));
  EXPECT_EQ(pressure.values, (std::vector<double>{1.0, 2.0, 30.0}));
  EXPECT_EQ(reader.dataset("watchpoints/a/coordinates").values,
            (std::vector<double>{0.005, 0.0, 0.02}));
}

}  // namespace
}  // namespace cocopp

// ResultsReader: the layout read back as written, and every failure an error that names the
// file and the object, never a silent zero.
#include <gtest/gtest.h>

#include <fstream>
#include <functional>

#include "coupler/results/results_reader.hpp"
#include "tests/unit/coupler/results/results_fixture.hpp"

using namespace cocopp;
using namespace cocopp::test;

namespace {

class ResultsReaderTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test_directory(); }
  std::filesystem::path dir_;
};

std::string error_of(const std::function<void()>& read) {
  try {
    read();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_F(ResultsReaderTest, ReadsTheLayout) {
  const auto file = dir_ / "run.h5";
  write_run(file, 3);
  const ResultsReader reader(file);
  EXPECT_EQ(reader.status(), "completed");
  EXPECT_DOUBLE_EQ(reader.delta_t(), 0.01);
  EXPECT_EQ(reader.steps(), (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(reader.members("x"), (std::vector<std::string>{"inlet", "wall"}));
  EXPECT_TRUE(reader.has("x/wall/displacement"));
  EXPECT_FALSE(reader.has("x/wall/pressure"));
  EXPECT_FALSE(reader.has("nowhere/at/all"));
  EXPECT_FALSE(reader.has(""));
  EXPECT_TRUE(reader.has_attribute("/", "delta_t"));
  EXPECT_FALSE(reader.has_attribute("/", "colour"));

  const auto pressure = reader.variable("y", "pressure");
  ASSERT_EQ(pressure.size(), 2u);
  EXPECT_EQ(pressure.at("wall").shape, (ResultsReader::Shape{3, 4, 1}));
  EXPECT_EQ(pressure.at("wall").row_size(), 4u);
  // Step 3's inlet pressure: y's last block (offset 16), as fill() set it.
  Interfaces expected = make_interfaces();
  fill(expected, 3);
  EXPECT_DOUBLE_EQ(pressure.at("inlet").values[2 * 2 + 1], expected.y.data()[17]);
  EXPECT_EQ(reader.variable("y", "traction").size(), 1u);  // the inlet has no traction
}

TEST_F(ResultsReaderTest, AMissingFileIsAnErrorNamingIt) {
  const auto file = dir_ / "absent.h5";
  const std::string message = error_of([&] { ResultsReader reader(file); });
  EXPECT_NE(message.find("cannot read the results file " + file.string()), std::string::npos)
      << message;
  EXPECT_NE(message.find("no such file"), std::string::npos) << message;
}

TEST_F(ResultsReaderTest, AFileThatIsNotHdf5IsAnError) {
  const auto file = dir_ / "text.h5";
  std::ofstream(file) << "not HDF5\n";
  const std::string message = error_of([&] { ResultsReader reader(file); });
  EXPECT_NE(message.find(file.string()), std::string::npos) << message;
  EXPECT_NE(message.find("opening failed"), std::string::npos) << message;
}

TEST_F(ResultsReaderTest, MissingObjectsAreErrorsNamingThem) {
  const auto file = dir_ / "run.h5";
  write_run(file, 1);
  const ResultsReader reader(file);
  const std::string dataset = error_of([&] { reader.dataset("x/wall/pressure"); });
  EXPECT_NE(dataset.find(file.string()), std::string::npos) << dataset;
  EXPECT_NE(dataset.find("no dataset x/wall/pressure"), std::string::npos) << dataset;
  const std::string attribute = error_of([&] { reader.number("/", "colour"); });
  EXPECT_NE(attribute.find("attribute /@colour"), std::string::npos) << attribute;
  const std::string strings = error_of([&] { reader.strings("x", "colour"); });
  EXPECT_NE(strings.find("attribute x@colour"), std::string::npos) << strings;
  EXPECT_NE(error_of([&] { reader.bools("steps/absent"); }).find("no dataset steps/absent"),
            std::string::npos);
  EXPECT_TRUE(reader.members("absent").empty());
}

TEST_F(ResultsReaderTest, AFileStillBeingWrittenShowsTheFlushedSteps) {
  const auto file = dir_ / "run.h5";
  auto writer = write_run(file, 2, "");
  std::filesystem::copy_file(file, dir_ / "copy.h5");
  const ResultsReader reader(dir_ / "copy.h5");
  EXPECT_EQ(reader.status(), "running");
  EXPECT_EQ(reader.steps(), (std::vector<int>{1, 2}));
}

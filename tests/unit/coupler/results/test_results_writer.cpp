// ResultsWriter: the HDF5 file is read back with the C API and checked against the layout in
// docs/results.md.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <csignal>
#include <fstream>

#include "coupler/results/results_writer.hpp"
#include "tests/unit/coupler/results/results_fixture.hpp"

namespace cocopp::test {
namespace {

using Shape = std::vector<hsize_t>;

class ResultsWriterTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test_directory(); }
  std::filesystem::path dir_;
};

/// "2026-11-22T00:37:54Z" (no std::regex: GCC 12 warns falsely on it under sanitizers).
bool is_iso_utc_time(const std::string& text) {
  const std::string shape = "dddd-dd-ddTdd:dd:ddZ";
  if (text.size() != shape.size()) return false;
  for (std::size_t i = 0; i < shape.size(); ++i)
    if (shape[i] == 'd' ? !std::isdigit(static_cast<unsigned char>(text[i])) : text[i] != shape[i])
      return false;
  return true;
}

TEST_F(ResultsWriterTest, WritesRunAttributes) {
  const auto file = dir_ / "run.h5";
  write_run(file, 3);
  const H5Handle h5 = open_file(file);
  ASSERT_TRUE(h5.valid());
  const hid_t f = h5.get();
  EXPECT_EQ(read_string(f, "/", "cocopp_version"), "0.1.0");
  EXPECT_EQ(read_string(f, "/", "case_file"), "examples/tube/case.yaml");
  EXPECT_EQ(read_string(f, "/", "coupled_solver"), "iqni");
  EXPECT_EQ(read_strings(f, "/", "solver_names"),
            (std::vector<std::string>{"tube_flow", "tube_structure"}));
  EXPECT_DOUBLE_EQ(read_number(f, "/", "delta_t"), 0.01);
  EXPECT_EQ(read_number(f, "/", "timestep_start"), 0);
  EXPECT_EQ(read_number(f, "/", "number_of_timesteps"), 3);
  EXPECT_TRUE(is_iso_utc_time(read_string(f, "/", "created")));
  EXPECT_TRUE(is_iso_utc_time(read_string(f, "/", "finished")));
  EXPECT_EQ(read_string(f, "/", "status"), "completed");
  EXPECT_EQ(read_string(f, "/", "message"), "all 3 steps done");
  EXPECT_EQ(read_number(f, "/", "steps_written"), 3);
}

TEST_F(ResultsWriterTest, WritesModelPartsAndBlockLayout) {
  const auto file = dir_ / "run.h5";
  write_run(file, 2);
  const H5Handle h5 = open_file(file);
  const hid_t f = h5.get();
  EXPECT_EQ(read_strings(f, "x", "model_parts"), (std::vector<std::string>{"wall", "inlet"}));
  EXPECT_EQ(read_number(f, "x", "size"), 18);
  EXPECT_EQ(read_strings(f, "y", "block_model_part"),
            (std::vector<std::string>{"wall", "wall", "inlet"}));
  EXPECT_EQ(read_strings(f, "y", "block_variable"),
            (std::vector<std::string>{"pressure", "traction", "pressure"}));
  EXPECT_EQ(read_numbers(f, "y", "block_offset"), (std::vector<double>{0, 4, 16}));
  EXPECT_EQ(read_numbers(f, "y", "block_size"), (std::vector<double>{4, 12, 2}));
  EXPECT_EQ(read_numbers(f, "y", "block_points"), (std::vector<double>{4, 4, 2}));
  EXPECT_EQ(read_numbers(f, "y", "block_components"), (std::vector<double>{1, 3, 1}));

  const Interfaces interfaces = make_interfaces();
  const ModelPart& inlet = *interfaces.x.parts()[1].model_part;
  const Array ids = read_dataset(f, "x/inlet/ids");
  EXPECT_EQ(ids.shape, Shape{2});
  EXPECT_EQ(ids.values, (std::vector<double>{inlet.ids[0] * 1.0, inlet.ids[1] * 1.0}));
  const Array coordinates = read_dataset(f, "y/inlet/coordinates");
  EXPECT_EQ(coordinates.shape, (Shape{2, 3}));
  EXPECT_DOUBLE_EQ(coordinates.values[5], inlet.coordinates(1, 2));
  EXPECT_EQ(read_string(f, "x/wall/coordinates", "unit"), "m");
}

TEST_F(ResultsWriterTest, InterfaceDataHasOneRowPerStep) {
  const auto file = dir_ / "run.h5";
  write_run(file, 3);
  const H5Handle h5 = open_file(file);
  const hid_t f = h5.get();
  EXPECT_EQ(read_dataset(f, "x/wall/displacement").shape, (Shape{3, 4, 3}));
  EXPECT_EQ(read_dataset(f, "x/inlet/displacement").shape, (Shape{3, 2, 3}));
  EXPECT_EQ(read_dataset(f, "y/wall/pressure").shape, (Shape{3, 4, 1}));
  EXPECT_EQ(read_dataset(f, "y/wall/traction").shape, (Shape{3, 4, 3}));
  EXPECT_EQ(read_string(f, "x/wall/displacement", "unit"), "m");
  EXPECT_EQ(read_string(f, "y/wall/pressure", "unit"), "Pa");

  // Rebuild the flattened vectors from the block description and compare with what was set.
  Interfaces expected = make_interfaces();
  for (const char* name : {"x", "y"}) {
    const auto parts = read_strings(f, name, "block_model_part");
    const auto variables = read_strings(f, name, "block_variable");
    const auto offsets = read_numbers(f, name, "block_offset");
    const auto sizes = read_numbers(f, name, "block_size");
    for (int step = 1; step <= 3; ++step) {
      fill(expected, step);
      const Interface& interface = std::string(name) == "x" ? expected.x : expected.y;
      for (std::size_t b = 0; b < parts.size(); ++b) {
        const Array data = read_dataset(f, std::string(name) + "/" + parts[b] + "/" + variables[b]);
        const auto per_row = static_cast<std::size_t>(sizes[b]);
        for (std::size_t k = 0; k < per_row; ++k)
          ASSERT_DOUBLE_EQ(data.values[(step - 1) * per_row + k],
                           interface.data()[static_cast<Eigen::Index>(offsets[b] + k)])
              << name << " block " << b << " step " << step << " value " << k;
      }
    }
  }
}

TEST_F(ResultsWriterTest, StepDatasets) {
  const auto file = dir_ / "run.h5";
  write_run(file, 3);
  const H5Handle h5 = open_file(file);
  const hid_t f = h5.get();
  EXPECT_EQ(read_dataset(f, "steps/step").values, (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(read_dataset(f, "steps/iterations").values, (std::vector<double>{3, 1, 2}));
  EXPECT_EQ(read_bools(f, "steps/converged"), (std::vector<int>{1, 0, 1}));
  const Array time = read_dataset(f, "steps/time");
  ASSERT_EQ(time.shape, Shape{3});
  EXPECT_DOUBLE_EQ(time.values[2], 0.03);
  const Array solver_times = read_dataset(f, "steps/solver_times");
  ASSERT_EQ(solver_times.shape, (Shape{3, 2}));
  EXPECT_DOUBLE_EQ(solver_times.values[2 * 2 + 1], make_record(3).solver_times[1]);
  EXPECT_DOUBLE_EQ(read_dataset(f, "steps/wall_time").values[1], 0.2);
  EXPECT_DOUBLE_EQ(read_dataset(f, "steps/coupler_time").values[1], make_record(2).coupler_time);
  EXPECT_EQ(read_string(f, "steps/wall_time", "unit"), "s");
}

TEST_F(ResultsWriterTest, ResidualsAreRagged) {
  const auto file = dir_ / "run.h5";
  write_run(file, 4);
  const H5Handle h5 = open_file(file);
  const hid_t f = h5.get();
  const Array norms = read_dataset(f, "residuals/norms");
  const Array offset = read_dataset(f, "residuals/offset");
  const Array count = read_dataset(f, "residuals/count");
  EXPECT_EQ(offset.values, (std::vector<double>{0, 3, 4, 6}));
  EXPECT_EQ(count.values, (std::vector<double>{3, 1, 2, 3}));
  ASSERT_EQ(norms.shape, Shape{9});
  for (int step = 1; step <= 4; ++step) {
    const auto expected = make_record(step).residual_norms;
    for (std::size_t i = 0; i < expected.size(); ++i)
      EXPECT_DOUBLE_EQ(norms.values[offset.values[step - 1] + i], expected[i]);
  }
}

TEST_F(ResultsWriterTest, CopyTakenAfterFlushWhileOpenIsReadable) {
  const auto file = dir_ / "run.h5";
  const auto copy = dir_ / "copy.h5";
  auto writer = write_run(file, 2, "");  // still open
  std::filesystem::copy_file(file, copy);
  {
    const H5Handle h5 = open_file(copy);
    ASSERT_TRUE(h5.valid()) << "a copy of a flushed, still open results file must open";
    const hid_t f = h5.get();
    EXPECT_EQ(read_string(f, "/", "status"), "running");
    EXPECT_EQ(read_dataset(f, "steps/step").values, (std::vector<double>{1, 2}));
    EXPECT_EQ(read_dataset(f, "x/wall/displacement").shape, (Shape{2, 4, 3}));
    EXPECT_EQ(read_dataset(f, "residuals/norms").shape, Shape{4});
    Interfaces expected = make_interfaces();
    fill(expected, 2);
    EXPECT_DOUBLE_EQ(read_dataset(f, "y/inlet/pressure").values[3], expected.y.data()[17]);
  }
  Interfaces interfaces = make_interfaces();
  fill(interfaces, 3);
  writer->write_step(make_record(3), interfaces.x, interfaces.y);
  writer->close("completed", "");
  const H5Handle h5 = open_file(file);
  EXPECT_EQ(read_dataset(h5.get(), "steps/step").shape, Shape{3});
}

TEST_F(ResultsWriterTest, AKilledRunLeavesAReadableFile) {
  const auto file = dir_ / "run.h5";
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    auto writer = write_run(file, 2, "");
    ::kill(::getpid(), SIGKILL);  // no destructor, no close: as if the machine killed the run
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
  const H5Handle h5 = open_file(file);
  ASSERT_TRUE(h5.valid());
  EXPECT_EQ(read_string(h5.get(), "/", "status"), "running");
  EXPECT_EQ(read_dataset(h5.get(), "steps/step").values, (std::vector<double>{1, 2}));
  EXPECT_EQ(read_dataset(h5.get(), "y/wall/traction").shape, (Shape{2, 4, 3}));
}

TEST_F(ResultsWriterTest, DestructorMarksTheFileIncomplete) {
  const auto file = dir_ / "run.h5";
  { auto writer = write_run(file, 1, ""); }
  const H5Handle h5 = open_file(file);
  EXPECT_EQ(read_string(h5.get(), "/", "status"), "incomplete");
  EXPECT_NE(read_string(h5.get(), "/", "message"), "");
  EXPECT_EQ(read_number(h5.get(), "/", "steps_written"), 1);
}

TEST_F(ResultsWriterTest, CloseTwiceKeepsTheFirstStatus) {
  const auto file = dir_ / "run.h5";
  auto writer = write_run(file, 1, "diverged");
  writer->close("completed", "ignored");
  EXPECT_FALSE(writer->is_open());
  const H5Handle h5 = open_file(file);
  EXPECT_EQ(read_string(h5.get(), "/", "status"), "diverged");
}

TEST_F(ResultsWriterTest, RejectsAStepOfAnotherLayoutWithoutWritingIt) {
  const auto file = dir_ / "run.h5";
  auto writer = write_run(file, 1, "");
  Interfaces interfaces = make_interfaces();
  EXPECT_THROW(writer->write_step(make_record(2), interfaces.y, interfaces.y),
               std::invalid_argument);
  StepRecord three_solvers = make_record(2);
  three_solvers.solver_times.push_back(1.0);
  EXPECT_THROW(writer->write_step(three_solvers, interfaces.x, interfaces.y),
               std::invalid_argument);
  EXPECT_EQ(writer->steps_written(), 1);
  writer->close("completed", "");
  const H5Handle h5 = open_file(file);
  EXPECT_EQ(read_dataset(h5.get(), "steps/step").shape, Shape{1});
  EXPECT_EQ(read_dataset(h5.get(), "x/wall/displacement").shape, (Shape{1, 4, 3}));
}

TEST_F(ResultsWriterTest, WriteAfterCloseIsALogicError) {
  auto writer = write_run(dir_ / "run.h5", 1);
  Interfaces interfaces = make_interfaces();
  EXPECT_THROW(writer->write_step(make_record(2), interfaces.x, interfaces.y), std::logic_error);
}

TEST_F(ResultsWriterTest, RejectsModelPartNamesHdf5CannotHold) {
  auto bad = model_part("left/wall", 2, 0.0);
  const Interface x({{bad, {"displacement"}}});
  const Interface y({{bad, {"pressure"}}});
  EXPECT_THROW(ResultsWriter(dir_ / "run.h5", make_run(1), x, y), std::invalid_argument);
}

TEST_F(ResultsWriterTest, CreatesTheDirectoryAndTruncatesAnOldFile) {
  const auto file = dir_ / "a" / "b" / "run.h5";
  write_run(file, 3);
  write_run(file, 1);
  const H5Handle h5 = open_file(file);
  EXPECT_EQ(read_dataset(h5.get(), "steps/step").shape, Shape{1});
}

TEST_F(ResultsWriterTest, FailureNamesTheFileAndPrintsNoHdf5Stack) {
  const auto file = dir_ / "is_a_directory.h5";
  std::filesystem::create_directories(file);
  const Interfaces interfaces = make_interfaces();
  ::testing::internal::CaptureStderr();
  try {
    ResultsWriter writer(file, make_run(1), interfaces.x, interfaces.y);
    ADD_FAILURE() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST_F(ResultsWriterTest, HandlesEmptyModelPartsEmptyResidualsAndBadUtf8) {
  const auto file = dir_ / "run.h5";
  const auto empty = model_part("empty", 0, 0.0);
  const auto wall = model_part("wall", 3, 0.0);
  Interface x({{empty, {"displacement"}}, {wall, {"displacement"}}});
  Interface y({{empty, {"pressure"}}, {wall, {"pressure"}}});
  RunDescription run = make_run(1);
  run.solver_names.clear();
  ResultsWriter writer(file, run, x, y);
  StepRecord record;  // no iterations, no solver times
  record.step = 1;
  writer.write_step(record, x, y);
  writer.close("solver_failed", "solver said: \xff\xfe broken");
  const H5Handle h5 = open_file(file);
  const hid_t f = h5.get();
  EXPECT_EQ(read_dataset(f, "x/empty/displacement").shape, (Shape{1, 0, 3}));
  EXPECT_EQ(read_dataset(f, "y/wall/pressure").shape, (Shape{1, 3, 1}));
  EXPECT_EQ(read_dataset(f, "steps/solver_times").shape, (Shape{1, 0}));
  EXPECT_EQ(read_dataset(f, "residuals/norms").shape, Shape{0});
  EXPECT_EQ(read_dataset(f, "residuals/count").values, std::vector<double>{0});
  EXPECT_TRUE(read_strings(f, "/", "solver_names").empty());
  EXPECT_EQ(read_string(f, "/", "message"), "solver said: \xef\xbf\xbd\xef\xbf\xbd broken");
}

}  // namespace
}  // namespace cocopp::test

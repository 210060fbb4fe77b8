// ResultsWriter: the HDF5 file is read back with the C API and checked against the layout in
// docs/results.md.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <csignal>
#include <fstream>
#include <functional>

#include "coupler/results/results_writer.hpp"
#include "tests/support/error_message.hpp"
#include "tests/unit/coupler/results/results_fixture.hpp"

namespace cocopp::test {
namespace {

using Shape = ResultsReader::Shape;
using Array = ResultsReader::Array;

class ResultsWriterTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test_directory(); }
  std::filesystem::path dir_;
};

/// Runs `write` in a child process that then dies by SIGKILL (no destructor, no close: as if
/// the machine killed the run), and waits for it.
void written_by_a_killed_process(const std::function<void()>& write) {
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    write();
    ::kill(::getpid(), SIGKILL);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
}

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
  const ResultsReader f(file);
  EXPECT_EQ(f.string("/", "cocopp_version"), "0.1.0");
  EXPECT_EQ(f.string("/", "case_file"), "examples/tube/case.yaml");
  EXPECT_EQ(f.string("/", "coupled_solver"), "iqni");
  EXPECT_EQ(f.strings("/", "solver_names"),
            (std::vector<std::string>{"tube_flow", "tube_structure"}));
  EXPECT_DOUBLE_EQ(f.number("/", "delta_t"), 0.01);
  EXPECT_EQ(f.number("/", "timestep_start"), 0);
  EXPECT_EQ(f.number("/", "number_of_timesteps"), 3);
  EXPECT_TRUE(is_iso_utc_time(f.string("/", "created")));
  EXPECT_TRUE(is_iso_utc_time(f.string("/", "finished")));
  EXPECT_EQ(f.string("/", "status"), "completed");
  EXPECT_EQ(f.string("/", "message"), "all 3 steps done");
  EXPECT_EQ(f.number("/", "steps_written"), 3);
}

TEST_F(ResultsWriterTest, WritesModelPartsAndBlockLayout) {
  const auto file = dir_ / "run.h5";
  write_run(file, 2);
  const ResultsReader f(file);
  EXPECT_EQ(f.strings("x", "model_parts"), (std::vector<std::string>{"wall", "inlet"}));
  EXPECT_EQ(f.number("x", "size"), 18);
  EXPECT_EQ(f.strings("y", "block_model_part"),
            (std::vector<std::string>{"wall", "wall", "inlet"}));
  EXPECT_EQ(f.strings("y", "block_variable"),
            (std::vector<std::string>{"pressure", "traction", "pressure"}));
  EXPECT_EQ(f.numbers("y", "block_offset"), (std::vector<double>{0, 4, 16}));
  EXPECT_EQ(f.numbers("y", "block_size"), (std::vector<double>{4, 12, 2}));
  EXPECT_EQ(f.numbers("y", "block_points"), (std::vector<double>{4, 4, 2}));
  EXPECT_EQ(f.numbers("y", "block_components"), (std::vector<double>{1, 3, 1}));

  const Interfaces interfaces = make_interfaces();
  const ModelPart& inlet = *interfaces.x.parts()[1].model_part;
  const Array ids = f.dataset("x/inlet/ids");
  EXPECT_EQ(ids.shape, Shape{2});
  EXPECT_EQ(ids.values, (std::vector<double>{inlet.ids[0] * 1.0, inlet.ids[1] * 1.0}));
  const Array coordinates = f.dataset("y/inlet/coordinates");
  EXPECT_EQ(coordinates.shape, (Shape{2, 3}));
  EXPECT_DOUBLE_EQ(coordinates.values[5], inlet.coordinates(1, 2));
  EXPECT_EQ(f.string("x/wall/coordinates", "unit"), "m");
}

TEST_F(ResultsWriterTest, InterfaceDataHasOneRowPerStep) {
  const auto file = dir_ / "run.h5";
  write_run(file, 3);
  const ResultsReader f(file);
  EXPECT_EQ(f.dataset("x/wall/displacement").shape, (Shape{3, 4, 3}));
  EXPECT_EQ(f.dataset("x/inlet/displacement").shape, (Shape{3, 2, 3}));
  EXPECT_EQ(f.dataset("y/wall/pressure").shape, (Shape{3, 4, 1}));
  EXPECT_EQ(f.dataset("y/wall/traction").shape, (Shape{3, 4, 3}));
  EXPECT_EQ(f.string("x/wall/displacement", "unit"), "m");
  EXPECT_EQ(f.string("y/wall/pressure", "unit"), "Pa");

  // Rebuild the flattened vectors from the block description and compare with what was set.
  Interfaces expected = make_interfaces();
  for (const char* name : {"x", "y"}) {
    const auto parts = f.strings(name, "block_model_part");
    const auto variables = f.strings(name, "block_variable");
    const auto offsets = f.numbers(name, "block_offset");
    const auto sizes = f.numbers(name, "block_size");
    for (int step = 1; step <= 3; ++step) {
      fill(expected, step);
      const Interface& interface = std::string(name) == "x" ? expected.x : expected.y;
      for (std::size_t b = 0; b < parts.size(); ++b) {
        const Array data = f.dataset(std::string(name) + "/" + parts[b] + "/" + variables[b]);
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
  const ResultsReader f(file);
  EXPECT_EQ(f.dataset("steps/step").values, (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(f.dataset("steps/iterations").values, (std::vector<double>{3, 1, 2}));
  EXPECT_EQ(f.bools("steps/converged"), (std::vector<int>{1, 0, 1}));
  const Array time = f.dataset("steps/time");
  ASSERT_EQ(time.shape, Shape{3});
  EXPECT_DOUBLE_EQ(time.values[2], 0.03);
  const Array solver_times = f.dataset("steps/solver_times");
  ASSERT_EQ(solver_times.shape, (Shape{3, 2}));
  EXPECT_DOUBLE_EQ(solver_times.values[2 * 2 + 1], make_record(3).solver_times[1]);
  EXPECT_DOUBLE_EQ(f.dataset("steps/wall_time").values[1], 0.2);
  EXPECT_DOUBLE_EQ(f.dataset("steps/coupler_time").values[1], make_record(2).coupler_time);
  EXPECT_EQ(f.string("steps/wall_time", "unit"), "s");
}

TEST_F(ResultsWriterTest, ResidualsAreRagged) {
  const auto file = dir_ / "run.h5";
  write_run(file, 4);
  const ResultsReader f(file);
  const Array norms = f.dataset("residuals/norms");
  const Array offset = f.dataset("residuals/offset");
  const Array count = f.dataset("residuals/count");
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
    const ResultsReader f(copy);
    EXPECT_EQ(f.string("/", "status"), "running");
    EXPECT_EQ(f.dataset("steps/step").values, (std::vector<double>{1, 2}));
    EXPECT_EQ(f.dataset("x/wall/displacement").shape, (Shape{2, 4, 3}));
    EXPECT_EQ(f.dataset("residuals/norms").shape, Shape{4});
    Interfaces expected = make_interfaces();
    fill(expected, 2);
    EXPECT_DOUBLE_EQ(f.dataset("y/inlet/pressure").values[3], expected.y.data()[17]);
  }
  Interfaces interfaces = make_interfaces();
  fill(interfaces, 3);
  writer->write_step(make_record(3), interfaces.x, interfaces.y);
  writer->close("completed", "");
  const ResultsReader h5(file);
  EXPECT_EQ(h5.dataset("steps/step").shape, Shape{3});
}

TEST_F(ResultsWriterTest, AKilledRunLeavesAReadableFile) {
  const auto file = dir_ / "run.h5";
  // released, not destroyed: the process dies with the file open
  written_by_a_killed_process([&] { (void)write_run(file, 2, "").release(); });
  const ResultsReader h5(file);
  EXPECT_EQ(h5.string("/", "status"), "running");
  EXPECT_EQ(h5.dataset("steps/step").values, (std::vector<double>{1, 2}));
  EXPECT_EQ(h5.dataset("y/wall/traction").shape, (Shape{2, 4, 3}));
}

// With a write interval (settings.results_write_interval), steps are kept in memory and written
// together: the file holds the same datasets as one written step by step, and the kept steps
// appear at write_kept_steps() and close().
TEST_F(ResultsWriterTest, KeptStepsAreWrittenTogetherAsIfStepByStep) {
  constexpr int kSteps = 5;
  const auto step_by_step = dir_ / "step_by_step.h5";
  write_run(step_by_step, kSteps);
  const auto kept = dir_ / "kept.h5";
  const auto copy = dir_ / "copy.h5";
  Interfaces interfaces = make_interfaces();
  ResultsWriter writer(kept, make_run(kSteps), interfaces.x, interfaces.y);
  writer.set_write_interval(3600.0);
  auto write_steps = [&](int first, int last) {
    for (int step = first; step <= last; ++step) {
      fill(interfaces, step);
      writer.write_step(make_record(step), interfaces.x, interfaces.y);
    }
  };
  auto steps_on_disk = [&] {
    std::filesystem::remove(copy);
    std::filesystem::copy_file(kept, copy);
    return ResultsReader(copy).dataset("steps/step").values;
  };
  write_steps(1, 2);
  EXPECT_TRUE(steps_on_disk().empty());
  EXPECT_EQ(writer.steps_written(), 2);
  writer.write_kept_steps();
  EXPECT_EQ(steps_on_disk(), (std::vector<double>{1, 2}));
  write_steps(3, kSteps);
  EXPECT_EQ(steps_on_disk(), (std::vector<double>{1, 2}));
  writer.close("completed", "all 5 steps done");
  EXPECT_EQ(writer.steps_written(), kSteps);

  const ResultsReader expected(step_by_step), actual(kept);
  for (const char* name :
       {"x/wall/displacement", "x/inlet/displacement", "y/wall/pressure", "y/wall/traction",
        "y/inlet/pressure", "steps/step", "steps/time", "steps/iterations", "steps/wall_time",
        "steps/coupler_time", "steps/solver_times", "residuals/norms", "residuals/offset",
        "residuals/count"}) {
    EXPECT_EQ(actual.dataset(name).shape, expected.dataset(name).shape) << name;
    EXPECT_EQ(actual.dataset(name).values, expected.dataset(name).values) << name;
  }
  EXPECT_EQ(actual.bools("steps/converged"), expected.bools("steps/converged"));
  EXPECT_EQ(actual.numbers("/", "steps_written"), expected.numbers("/", "steps_written"));
}

TEST_F(ResultsWriterTest, AKilledRunWithKeptStepsLeavesTheStepsOfTheLastWrite) {
  const auto file = dir_ / "run.h5";
  written_by_a_killed_process([&] {
    Interfaces interfaces = make_interfaces();
    // never destroyed: the process dies with the file open
    auto* writer = new ResultsWriter(file, make_run(3), interfaces.x, interfaces.y);
    writer->set_write_interval(3600.0);
    for (int step = 1; step <= 3; ++step) {
      fill(interfaces, step);
      writer->write_step(make_record(step), interfaces.x, interfaces.y);
      if (step == 2) writer->write_kept_steps();
    }
  });
  const ResultsReader h5(file);
  EXPECT_EQ(h5.string("/", "status"), "running");
  EXPECT_EQ(h5.dataset("steps/step").values, (std::vector<double>{1, 2}));
  EXPECT_EQ(h5.dataset("residuals/offset").values, (std::vector<double>{0, 3}));
}

TEST_F(ResultsWriterTest, DestructorMarksTheFileIncomplete) {
  const auto file = dir_ / "run.h5";
  { auto writer = write_run(file, 1, ""); }
  const ResultsReader h5(file);
  EXPECT_EQ(h5.string("/", "status"), "incomplete");
  EXPECT_NE(h5.string("/", "message"), "");
  EXPECT_EQ(h5.number("/", "steps_written"), 1);
}

TEST_F(ResultsWriterTest, CloseTwiceKeepsTheFirstStatus) {
  const auto file = dir_ / "run.h5";
  auto writer = write_run(file, 1, "diverged");
  writer->close("completed", "ignored");
  EXPECT_FALSE(writer->is_open());
  const ResultsReader h5(file);
  EXPECT_EQ(h5.string("/", "status"), "diverged");
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
  const ResultsReader h5(file);
  EXPECT_EQ(h5.dataset("steps/step").shape, Shape{1});
  EXPECT_EQ(h5.dataset("x/wall/displacement").shape, (Shape{1, 4, 3}));
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
  const ResultsReader h5(file);
  EXPECT_EQ(h5.dataset("steps/step").shape, Shape{1});
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
  const ResultsReader f(file);
  EXPECT_EQ(f.dataset("x/empty/displacement").shape, (Shape{1, 0, 3}));
  EXPECT_EQ(f.dataset("y/wall/pressure").shape, (Shape{1, 3, 1}));
  EXPECT_EQ(f.dataset("steps/solver_times").shape, (Shape{1, 0}));
  EXPECT_EQ(f.dataset("residuals/norms").shape, Shape{0});
  EXPECT_EQ(f.dataset("residuals/count").values, std::vector<double>{0});
  EXPECT_TRUE(f.strings("/", "solver_names").empty());
  EXPECT_EQ(f.string("/", "message"), "solver said: \xef\xbf\xbd\xef\xbf\xbd broken");
}

// A restarted run continues the file after the saved step: rows after it (computed again now)
// are dropped, the residual norms with them, and new rows follow.
TEST_F(ResultsWriterTest, ContinuesAFileAfterAStepAndDropsTheRowsAfterIt) {
  const auto file = dir_ / "run.h5";
  write_run(file, 5, "");  // killed after step 5: still "running"
  Interfaces interfaces = make_interfaces();
  {
    ResultsWriter writer(file, make_run(5), interfaces.x, interfaces.y, 3);
    EXPECT_EQ(writer.steps_written(), 0);
    for (int step = 4; step <= 6; ++step) {
      fill(interfaces, 10 * step);  // other values than the first run's
      StepRecord record = make_record(step);
      record.residual_norms.push_back(7.0);  // one more iteration than the first run's
      ++record.iterations;
      writer.write_step(record, interfaces.x, interfaces.y);
    }
    EXPECT_EQ(writer.steps_written(), 3);
    writer.close("completed", "done");
  }
  const ResultsReader f(file);
  EXPECT_EQ(f.steps(), (std::vector<int>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(f.number("/", "restarted_after_step"), 3);
  EXPECT_EQ(f.number("/", "steps_written"), 6);
  EXPECT_EQ(f.string("/", "status"), "completed");
  const auto offsets = f.dataset("residuals/offset").values;
  const auto counts = f.dataset("residuals/count").values;
  const auto norms = f.dataset("residuals/norms").values;
  ASSERT_EQ(offsets.size(), 6u);
  for (std::size_t row = 0; row < 6; ++row) {
    const int step = static_cast<int>(row) + 1;
    const StepRecord expected = make_record(step);
    const std::size_t count = expected.residual_norms.size() + (step > 3 ? 1 : 0);
    EXPECT_EQ(counts[row], double(count)) << "step " << step;
    if (row > 0) {
      EXPECT_EQ(offsets[row], offsets[row - 1] + counts[row - 1]);
    }
    EXPECT_EQ(norms[std::size_t(offsets[row])], expected.residual_norms[0]) << "step " << step;
  }
  EXPECT_EQ(norms.size(), std::size_t(offsets[5] + counts[5]));
  const auto pressure = f.dataset("y/inlet/pressure");
  ASSERT_EQ(pressure.shape, (Shape{6, 2, 1}));
  Interfaces check = make_interfaces();
  for (int step = 1; step <= 6; ++step) {
    fill(check, step > 3 ? 10 * step : step);
    EXPECT_EQ(pressure.values[2 * std::size_t(step - 1)], check.y.values("inlet", "pressure")(0, 0))
        << "step " << step;
  }
}

// A run that stopped in step 5 is continued after step 3 and stops in a step of its own: the
// file then says where the continued run stopped, not the first run's step.
TEST_F(ResultsWriterTest, AContinuedRunReplacesTheUnfinishedStepOfTheRunItContinues) {
  const auto file = dir_ / "run.h5";
  Interfaces interfaces = make_interfaces();
  {
    ResultsWriter writer(file, make_run(5), interfaces.x, interfaces.y);
    for (int step = 1; step <= 4; ++step) {
      fill(interfaces, step);
      writer.write_step(make_record(step), interfaces.x, interfaces.y);
    }
    writer.write_unfinished_step(5, 0.5, {1.0, 2.0});
    writer.close("diverged", "step 5");
  }
  {
    ResultsWriter writer(file, make_run(8), interfaces.x, interfaces.y, 3);
    for (int step = 4; step <= 6; ++step) {
      fill(interfaces, 10 * step);
      writer.write_step(make_record(step), interfaces.x, interfaces.y);
    }
    writer.write_unfinished_step(7, 0.7, {3.0});
    writer.close("diverged", "step 7");
  }
  const ResultsReader f(file);
  EXPECT_EQ(f.steps(), (std::vector<int>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(f.number("unfinished_step", "step"), 7);
  EXPECT_EQ(f.dataset("unfinished_step/residual_norms").values, (std::vector<double>{3.0}));
}

/// The link names of `group` in the order they were created.
std::vector<std::string> in_creation_order(const std::filesystem::path& file,
                                           const std::string& group) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  H5G_info_t info{};
  H5Gget_info_by_name(f, group.c_str(), &info, H5P_DEFAULT);
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    char name[64] = {};
    H5Lget_name_by_idx(f, group.c_str(), H5_INDEX_CRT_ORDER, H5_ITER_INC, i, name, sizeof name,
                       H5P_DEFAULT);
    names.emplace_back(name);
  }
  H5Fclose(f);
  return names;
}

// A continued file is written anew from the kept steps (a run killed in a flush can leave
// metadata that reads but cannot be written to): everything else is as the first run wrote it.
TEST_F(ResultsWriterTest, AContinuedFileKeepsTheFirstRunsAttributesUnitsAndOrder) {
  const auto file = dir_ / "run.h5";
  write_run(file, 5, "");
  const auto order = in_creation_order(file, "x");
  ASSERT_EQ(order, (std::vector<std::string>{"wall", "inlet"}));  // not name order
  const ResultsReader before(file);
  Interfaces interfaces = make_interfaces();
  {
    ResultsWriter writer(file, make_run(5), interfaces.x, interfaces.y, 3);
    EXPECT_FALSE(std::filesystem::exists(dir_ / "run.h5.continued"));
    writer.close("completed", "done");
  }
  const ResultsReader after(file);
  EXPECT_EQ(in_creation_order(file, "x"), order);
  EXPECT_EQ(after.steps(), (std::vector<int>{1, 2, 3}));
  for (const char* name : {"cocopp_version", "case_file", "coupled_solver", "created"})
    EXPECT_EQ(after.string("/", name), before.string("/", name)) << name;
  EXPECT_EQ(after.strings("/", "solver_names"), before.strings("/", "solver_names"));
  EXPECT_EQ(after.number("/", "delta_t"), before.number("/", "delta_t"));
  EXPECT_EQ(after.string("steps/time", "unit"), "s");
  EXPECT_EQ(after.dataset("x/wall/coordinates").values,
            before.dataset("x/wall/coordinates").values);
  const std::vector<double> converged = before.dataset("steps/converged").values;
  ASSERT_EQ(converged.size(), 5u);
  EXPECT_EQ(after.dataset("steps/converged").values,
            std::vector<double>(converged.begin(), converged.begin() + 3));
  // A copy is continued like the first file (its groups' link storage is its own: a copy made
  // with the source's creation lists pointed into the source and could not be read again).
  {
    ResultsWriter writer(file, make_run(5), interfaces.x, interfaces.y, 2);
    writer.close("completed", "again");
  }
  EXPECT_EQ(ResultsReader(file).steps(), (std::vector<int>{1, 2}));
  EXPECT_EQ(in_creation_order(file, "x"), order);
}

TEST_F(ResultsWriterTest, ContinuingAFileThatDoesNotFitSaysWhy) {
  const auto file = dir_ / "run.h5";
  write_run(file, 3);
  Interfaces interfaces = make_interfaces();
  const auto message = [&](const std::filesystem::path& path, const RunDescription& run,
                           const Interface& x, int step) {
    return cocopp::testing::error_message<std::runtime_error>(
        [&] { ResultsWriter writer(path, run, x, interfaces.y, step); });
  };
  const auto expect_in = [](const std::string& text, const std::string& part) {
    EXPECT_NE(text.find(part), std::string::npos) << text;
  };
  expect_in(message(dir_ / "missing.h5", make_run(3), interfaces.x, 2), "it is not there");
  expect_in(message(file, make_run(3), interfaces.x, 4), "it holds steps 1 to 3");
  RunDescription other = make_run(3);
  other.delta_t = 0.02;
  expect_in(message(file, other, interfaces.x, 2), "delta_t");
  const Interface more_points({{model_part("wall", 5, 0.0), {"displacement"}},
                               {model_part("inlet", 2, -0.01), {"displacement"}}});
  expect_in(message(file, make_run(3), more_points, 2),
            "x/wall/displacement does not have the layout");
  // The file is untouched by the failed attempts.
  EXPECT_EQ(ResultsReader(file).steps(), (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(ResultsReader(file).string("/", "status"), "completed");
}

}  // namespace
}  // namespace cocopp::test

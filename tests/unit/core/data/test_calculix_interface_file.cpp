// The interface file between the calculix wrapper and cocopp-ccx: what one side writes, the
// other reads back exactly; a damaged file is named with what is wrong.
#include <gtest/gtest.h>

#include <string>

#include "core/data/calculix_interface_file.hpp"
#include "tests/support/error_message.hpp"
#include "tests/support/temporary_directory.hpp"

namespace cocopp::calculix {
namespace {

using cocopp::testing::error_message;
using cocopp::testing::read_text;
using cocopp::testing::TemporaryDirectory;
using cocopp::testing::write_text;

TEST(CalculixInterfaceFile, ReadsBackWhatWasWritten) {
  InterfaceFile written;
  written.ramp = false;
  written.initial_increment = std::stod(ccx_number(1.0 / 3.0));
  written.force_scale = std::stod(ccx_number(1.0 / 180.0));
  written.linear = true;
  written.pressure_faces = {{12, 3}, {13, 4}};
  written.face_offset = 2;
  written.force_nodes = {1, 5, 9};
  written.force_dofs = 2;
  written.displacement_nodes = {5, 9};
  TemporaryDirectory directory;
  const auto file = directory / InterfaceFile::kName;
  written.write(file);
  EXPECT_EQ(read_text(file).substr(0, 28), "amplitude step\ninitial_incre");

  const InterfaceFile read = InterfaceFile::read(file);
  EXPECT_EQ(read.ramp, false);
  EXPECT_EQ(read.initial_increment, written.initial_increment);
  EXPECT_EQ(read.force_scale, written.force_scale);
  EXPECT_EQ(read.linear, true);
  EXPECT_EQ(read.pressure_faces, written.pressure_faces);
  EXPECT_EQ(read.face_offset, 2);
  EXPECT_EQ(read.force_nodes, written.force_nodes);
  EXPECT_EQ(read.force_dofs, 2);
  EXPECT_EQ(read.displacement_nodes, written.displacement_nodes);
}

TEST(CalculixInterfaceFile, ADamagedFileIsNamedWithWhatIsWrong) {
  TemporaryDirectory directory;
  const auto file = directory / "interface.txt";
  const auto error = [&](const std::string& text) {
    write_text(file, text);
    return error_message<std::runtime_error>([&] { InterfaceFile::read(file); });
  };
  EXPECT_NE(error("amplitude ramp\ninitial_incr 1\n")
                .find(file.string() + ": expected 'initial_increment', found 'initial_incr'"),
            std::string::npos);
  EXPECT_NE(error("amplitude sine\n").find("amplitude is ramp or step, not 'sine'"),
            std::string::npos);
  const std::string head = "amplitude ramp\ninitial_increment 1\nforce_scale 1\nlinear 0\n";
  EXPECT_NE(error(head + "pressure_faces -3 0\n").find("'pressure_faces' needs a count"),
            std::string::npos);
  EXPECT_NE(error(head + "pressure_faces 2 0\n1 3\n").find("truncated or not a number"),
            std::string::npos);
  EXPECT_NE(error_message<std::runtime_error>([&] {
              InterfaceFile::read(directory / "missing.txt");
            }).find("cannot read " + (directory / "missing.txt").string()),
            std::string::npos);
}

TEST(CalculixInterfaceFile, NumbersFitCcxsField) {
  EXPECT_EQ(ccx_number(0.25), "2.5000000000000E-01");
  EXPECT_EQ(ccx_number(1e-120), "0.");
  EXPECT_LE(ccx_number(-1.0 / 3.0).size(), 20u);
}

}  // namespace
}  // namespace cocopp::calculix

// The displacement drive's Newton step with the structure's surface compliance between its
// driven lines (DisplacementDrive::use_compliance, SurfaceCompliance): for a structure whose
// lines answer with exactly that compliance, one step returns the position where the
// structure balances the other solver's load, however the lines are coupled; one stiffness
// per line does not. And the file's errors name the file and line. No ccx: the reactions are
// the ones such a structure gives.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "solver_wrappers/calculix/displacement_drive.hpp"
#include "solver_wrappers/calculix/surface_compliance.hpp"
#include "tests/support/calculix_models.hpp"
#include "tests/support/error_message.hpp"
#include "tests/support/temporary_directory.hpp"

namespace cocopp::calculix {
namespace {

using cocopp::testing::error_message;
using cocopp::testing::SectorCylinder;
using cocopp::testing::TemporaryDirectory;
using cocopp::testing::write_text;

constexpr double kPressure = 1e6;  ///< Pa, the other solver's, on every face
constexpr double kWall = 1e-5;     ///< m: the wall's prescribed radial position, + a ramp

class DriveCompliance : public ::testing::Test {
 protected:
  DriveCompliance() {
    cylinder_.axial = 3;
    write_text(directory_ / "wall.inp", cylinder_.deck());
    deck_ =
        std::make_unique<InputDeck>(InputDeck::read(directory_ / "wall.inp", directory_.path()));
    loads_ = std::make_unique<InterfaceLoads>(*deck_, deck_->surface("INNER"));
    // Every node of the bore's faces may be driven: hoop lines of two or three nodes.
    for (const auto& face : loads_->geometry())
      for (const auto node : face.nodes) lines_[std::round(deck_->node(node).z() * 1e9)];
    for (const auto& face : loads_->geometry())
      for (const auto node : face.nodes) {
        auto& line = lines_[std::round(deck_->node(node).z() * 1e9)];
        if (std::find(line.begin(), line.end(), node) == line.end()) line.push_back(node);
      }
    for (const auto& [z, line] : lines_) nodes_.insert(nodes_.end(), line.begin(), line.end());
    std::sort(nodes_.begin(), nodes_.end());
    // A compliance that couples every line with every other (SPD): m/N.
    const auto count = static_cast<Eigen::Index>(lines_.size());
    compliance_.resize(count, count);
    for (Eigen::Index i = 0; i < count; ++i)
      for (Eigen::Index j = 0; j < count; ++j)
        compliance_(i, j) =
            1e-9 * (std::exp(-0.7 * std::abs(static_cast<double>(i - j))) + (i == j ? 0.5 : 0.0));
  }

  std::string compliance_file() const {
    std::string text = "# a test's compliance\nlines " + std::to_string(lines_.size()) + "\n";
    for (const auto& [z, line] : lines_) {
      for (const auto node : line) text += std::to_string(node) + " ";
      text += "\n";
    }
    text += "compliance " + std::to_string(lines_.size()) + "\n";
    for (Eigen::Index i = 0; i < compliance_.rows(); ++i) {
      for (Eigen::Index j = 0; j < compliance_.cols(); ++j)
        text += fmt::format("{:.17g} ", compliance_(i, j));
      text += "\n";
    }
    return text;
  }

  /// The drive with surface_stiffness the compliance's diagonal, inverted, per line area.
  std::unique_ptr<DisplacementDrive> drive() const {
    double area = 0.0;
    for (const auto& face : loads_->geometry()) area += face.area;
    const double line_area = area / static_cast<double>(lines_.size());
    return std::make_unique<DisplacementDrive>(*deck_, *loads_, nodes_, nodes_, 1,
                                               1.0 / (compliance_(0, 0) * line_area));
  }

  /// Every face covered by a film so thick that its stiffness is nil, the wall at kWall plus
  /// a ramp along the axis at every node.
  DisplacementDrive::Inputs inputs() const {
    const auto faces = static_cast<Eigen::Index>(loads_->faces().size());
    const auto nodes = static_cast<Eigen::Index>(nodes_.size());
    DisplacementDrive::Inputs in{Eigen::VectorXd::Constant(faces, kPressure),
                                 RowMatrix::Zero(faces, 3),
                                 RowMatrix(),
                                 Eigen::VectorXd::Constant(faces, 1e30),
                                 Eigen::VectorXd::Ones(faces),
                                 RowMatrix::Zero(nodes, 3)};
    for (Eigen::Index n = 0; n < nodes; ++n) {
      const Eigen::Vector3d x = deck_->node(nodes_[static_cast<std::size_t>(n)]);
      in.wall_displacement.row(n) =
          (kWall * (1.0 + 100.0 * x.z())) * Eigen::RowVector3d(x.x(), x.y(), 0).normalized();
    }
    return in;
  }

  /// The structure's answer where the drive put it: per line, the film's force on the line
  /// beyond the structure's balance is what the compliance gives for the line's distance
  /// from `balance` (the structure's balanced radial positions), split over its nodes.
  RowMatrix reactions(const DisplacementDrive& drive, const Eigen::VectorXd& balance) const {
    const auto count = static_cast<Eigen::Index>(lines_.size());
    Eigen::VectorXd offset(count);
    Eigen::Index i = 0;
    for (const auto& [z, line] : lines_) {
      offset[i] = prescribed(drive, line.front()) - balance[i];
      ++i;
    }
    const Eigen::VectorXd extra = compliance_.ldlt().solve(offset);
    RowMatrix reaction = RowMatrix::Zero(static_cast<Eigen::Index>(nodes_.size()), 3);
    i = 0;
    for (const auto& [z, line] : lines_) {
      for (const auto node : line) {
        const auto row = std::lower_bound(nodes_.begin(), nodes_.end(), node) - nodes_.begin();
        const double film = loads_->in_node_system(node, drive.film_forces().at(node)).x();
        reaction(row, 0) = film + extra[i] / static_cast<double>(line.size());
      }
      ++i;
    }
    return reaction;
  }

  /// The radial position the drive prescribed at `node`.
  double prescribed(const DisplacementDrive&, std::int64_t node) const {
    const Eigen::Vector3d x = deck_->node(node);
    return kWall * (1.0 + 100.0 * x.z());
  }

  /// The radial positions the drive returns, per line.
  Eigen::VectorXd returned_lines(const RowMatrix& returned) const {
    Eigen::VectorXd result(static_cast<Eigen::Index>(lines_.size()));
    Eigen::Index i = 0;
    for (const auto& [z, line] : lines_) {
      const auto row =
          std::lower_bound(nodes_.begin(), nodes_.end(), line.front()) - nodes_.begin();
      const Eigen::Vector3d x = deck_->node(line.front());
      result[i++] = returned.row(row).dot(Eigen::RowVector3d(x.x(), x.y(), 0).normalized());
    }
    return result;
  }

  Eigen::VectorXd step(DisplacementDrive& drive, const Eigen::VectorXd& balance) const {
    drive.plan(inputs(), {});
    const RowMatrix displacement = RowMatrix::Zero(static_cast<Eigen::Index>(nodes_.size()), 3);
    return returned_lines(drive.balance(displacement, reactions(drive, balance)));
  }

  Eigen::VectorXd balance() const {
    Eigen::VectorXd result(static_cast<Eigen::Index>(lines_.size()));
    for (Eigen::Index i = 0; i < result.size(); ++i)
      result[i] = 2e-5 + 3e-6 * std::sin(1.3 * static_cast<double>(i));
    return result;
  }

  SectorCylinder cylinder_;
  TemporaryDirectory directory_;
  std::unique_ptr<InputDeck> deck_;
  std::unique_ptr<InterfaceLoads> loads_;
  std::map<double, std::vector<std::int64_t>> lines_;  ///< by axial position (nm)
  std::vector<std::int64_t> nodes_;
  Eigen::MatrixXd compliance_;
};

TEST_F(DriveCompliance, OneStepLandsOnTheBalanceOfAStructureWithThatCompliance) {
  write_text(directory_ / "compliance.txt", compliance_file());
  auto drive = this->drive();
  drive->use_compliance(SurfaceCompliance::read(directory_ / "compliance.txt"), 1.0);
  const Eigen::VectorXd landed = step(*drive, balance());
  EXPECT_LT((landed - balance()).cwiseAbs().maxCoeff(), 1e-9 * balance().cwiseAbs().maxCoeff())
      << "returned " << landed.transpose() << "\nbalance " << balance().transpose();
}

TEST_F(DriveCompliance, OneStiffnessPerLineMissesTheCoupledBalance) {
  auto drive = this->drive();
  const Eigen::VectorXd landed = step(*drive, balance());
  EXPECT_GT((landed - balance()).cwiseAbs().maxCoeff(), 0.05 * (balance().maxCoeff() - kWall));
}

TEST_F(DriveCompliance, ASofterScaleStepsFurther) {
  // Twice the compliance: the structure taken for half as stiff, the step twice as long.
  write_text(directory_ / "compliance.txt", compliance_file());
  auto drive = this->drive();
  drive->use_compliance(SurfaceCompliance::read(directory_ / "compliance.txt"), 2.0);
  const Eigen::VectorXd landed = step(*drive, balance());
  Eigen::VectorXd start(landed.size());
  Eigen::Index i = 0;
  for (const auto& [z, line] : lines_) start[i++] = prescribed(*drive, line.front());
  const Eigen::VectorXd expected = start + 2.0 * (balance() - start);
  EXPECT_LT((landed - expected).cwiseAbs().maxCoeff(), 1e-9 * expected.cwiseAbs().maxCoeff());
}

TEST_F(DriveCompliance, RefusesAFileWithoutADrivableNode) {
  std::string text = compliance_file();
  const std::string first = std::to_string(lines_.begin()->second.front()) + " ";
  text.replace(text.find(first, text.find("lines")), first.size(), "");
  write_text(directory_ / "compliance.txt", text);
  auto drive = this->drive();
  const std::string message = error_message<DeckError>(
      [&] { drive->use_compliance(SurfaceCompliance::read(directory_ / "compliance.txt"), 1.0); });
  EXPECT_NE(message.find("node " + first + "may be driven"), std::string::npos) << message;
}

TEST_F(DriveCompliance, TheLogHasEachIterationsLines) {
  // drive_log: per balance, a header and per driven line its node, axial position, prescribed
  // value, imbalance, weight, film stiffness and move (what drive_pairs.py reads).
  auto drive = this->drive();
  drive->log_to(directory_ / "drive.log");
  drive->start_step(3);
  step(*drive, balance());
  step(*drive, balance());
  std::ifstream log(directory_ / "drive.log");
  std::vector<std::string> lines;
  for (std::string line; std::getline(log, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 2 * (lines_.size() + 1));
  EXPECT_EQ(lines[0], "# step 3 iteration 1");
  EXPECT_EQ(lines[lines_.size() + 1], "# step 3 iteration 2");
  std::istringstream first(lines[1]);
  double node = 0, axial = 0, prescribed = 0;
  first >> node >> axial >> prescribed;
  // A line is named by one of its nodes.
  const auto id = static_cast<std::int64_t>(node);
  EXPECT_TRUE(std::any_of(lines_.begin(), lines_.end(),
                          [&](const auto& line) {
                            return std::find(line.second.begin(), line.second.end(), id) !=
                                   line.second.end();
                          }))
      << "node " << id;
  EXPECT_NEAR(prescribed, this->prescribed(*drive, id), 1e-9 * kWall);
}

TEST(SurfaceComplianceFile, ErrorsNameTheFileAndLine) {
  TemporaryDirectory directory;
  const auto message = [&](const std::string& text) {
    write_text(directory / "c.txt", text);
    return error_message<DeckError>([&] { SurfaceCompliance::read(directory / "c.txt"); });
  };
  EXPECT_NE(message("# c\nlines 2\n1 2\n3\ncompliance 2\n1 0\n0\n")
                .find("c.txt:7: surface "
                      "compliance: row 2 has "
                      "fewer than 2"),
            std::string::npos);
  EXPECT_NE(message("lines 2\n1 2\n2\n").find("c.txt:3: surface compliance: node 2 is in two"),
            std::string::npos);
  EXPECT_NE(message("lines 1\n1\ncompliance 2\n")
                .find("c.txt:3: surface compliance: the "
                      "compliance must be 1 x 1"),
            std::string::npos);
  EXPECT_NE(message("lines 1\n1\n").find("ends before compliance"), std::string::npos);
  const auto read = [&](const std::string& text) {
    write_text(directory / "c.txt", text);
    return SurfaceCompliance::read(directory / "c.txt");
  };
  const SurfaceCompliance compliance = read("lines 2\n5 6\n7\ncompliance 2\n1 2\n3 4\n");
  EXPECT_EQ(*compliance.row_of(6), 0);
  EXPECT_EQ(*compliance.row_of(7), 1);
  EXPECT_FALSE(compliance.row_of(8));
  EXPECT_EQ(compliance.block({1, 0}), (Eigen::Matrix2d() << 4, 3, 2, 1).finished());
}

}  // namespace
}  // namespace cocopp::calculix

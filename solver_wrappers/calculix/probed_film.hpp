#pragma once
// ProbedFilm: a lubricant film's own sensitivity to its wall, measured by the film by finite
// differences (cocoppPimpleFoam with COCOPP_SENSITIVITY_PROBE, sensitivity_probe.cpp), as the
// displacement drive's film stiffness between its lines (`film_stiffness: probed`). The file
// holds the film's faces (axial position, radius, area, gap, radial and axial force) and, per
// hoop line of the film's wall moved radially, every face's radial force change per metre.
#include <Eigen/Core>
#include <filesystem>

namespace cocopp::calculix {

class ProbedFilm {
 public:
  /// Throws std::runtime_error naming the file and what is wrong.
  static ProbedFilm read(const std::filesystem::path& file);

  int step() const { return step_; }
  /// The film's stiffness between lines at `axial` (the structure's reference positions along
  /// the film's axis), N per m of move: K(l, m) = -weight(l) dq(axial(l) + offset) / d(move of
  /// line m), the moves carried to the film's lines by linear interpolation along the axis.
  /// `offset` (the film's axial position of the structure's 0) is found where the film's own
  /// 2 p / gap matches `local` (the lines' 2 p / gap from the mapped loads) best.
  Eigen::MatrixXd stiffness(const Eigen::VectorXd& axial, const Eigen::VectorXd& weight,
                            const Eigen::VectorXd& local) const;
  /// The offset of the last stiffness() (m).
  double offset() const { return offset_; }

 private:
  double find_offset(const Eigen::VectorXd& axial, const Eigen::VectorXd& local) const;

  int step_ = 0;
  Eigen::VectorXd face_axial_, face_local_;  ///< per film face: position, 2 p / gap (Pa/m)
  Eigen::VectorXd line_axial_;               ///< per probed film line
  Eigen::MatrixXd traction_;  ///< (line, face): radial traction change per m of move (Pa/m)
  mutable double offset_ = 0.0;
};

}  // namespace cocopp::calculix

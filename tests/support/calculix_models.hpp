#pragma once
// CalculiX decks of simple structures with known answers, for the CalculiX wrapper's tests and
// benchmark:
// - a thick-walled cylinder (inner radius ri, outer ro) as a thin sector of C3D20R elements with
//   a cylindrical *TRANSFORM and zero hoop displacement (axis z; runs with any ccx), or as an
//   axisymmetric CAX8 model (element_type CAX8 or CAX8R: x = radius, y = axis; restarts only
//   with cocopp's patched ccx). Surface INNER (faces on r = ri, loads), node sets INNERN (nodes
//   on r = ri), NALL, SUPPORT (the outer edge at the axial position 0); the CAX model also has
//   surface TOP and node set TOPN (the end at y = length).
// - a plane-strain strip of CPE8 elements (Lx x Ly, thickness t), on rollers at y = 0 (x held at
//   one corner): surface
//   TOP (faces on y = Ly) and node sets TOPN, BOTTOM.
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace cocopp::testing {

inline constexpr double kPi = 3.14159265358979323846;

/// An 8-node quadrilateral (CPE8, CAX8, ...) on a doubled grid of node ids id(i, j), with its
/// lower-left corner at (i, j): corners counter-clockwise, then the mid-side nodes.
template <class Id>
std::string quad8_nodes(const Id& id, int i, int j) {
  std::ostringstream out;
  out << id(i, j) << ", " << id(i + 2, j) << ", " << id(i + 2, j + 2) << ", " << id(i, j + 2)
      << ", " << id(i + 1, j) << ", " << id(i + 2, j + 1) << ", " << id(i + 1, j + 2) << ", "
      << id(i, j + 1);
  return out.str();
}

struct SectorCylinder {
  double ri = 0.01;
  double ro = 0.02;
  double length = 0.002;
  int radial = 8;
  int axial = 1;
  double angle_degrees = 1.0;
  /// The sector spans centre +- angle / 2: away from the x axis, so that local and global
  /// directions differ and a missing rotation into the *TRANSFORM system shows.
  double centre_degrees = 45.0;
  /// Ratio of the outermost to the innermost element's radial size (1: uniform).
  double grading = 1.0;
  double young = 200e9;
  double poisson = 0.3;
  double yield_stress = 0.0;  ///< > 0: elastic-perfectly plastic (von Mises)
  bool nlgeom = false;
  /// true: u_z = 0 at every node (plane strain); false: u_z = 0 on the SUPPORT edge only.
  bool plane_strain = true;
  std::string element_type = "C3D20R";
  double density = 0.0;                  ///< > 0: *DENSITY (for dynamic steps)
  std::string step_options;              ///< added to the *STEP line, e.g. ", AMPLITUDE=RAMP"
  std::string procedure = "*STATIC";     ///< e.g. "*DYNAMIC, DIRECT, ALPHA=0"
  std::string increments = "0.25, 1.0";  ///< the procedure's data line
  std::string extra_step_cards;          ///< e.g. *NODE PRINT cards for reactions

  int elements() const { return radial * axial; }

  double radius(int doubled_index) const {
    // Element sizes grow geometrically from ri to ro by `grading` overall.
    const double growth = radial > 1 ? std::pow(grading, 1.0 / (radial - 1)) : 1.0;
    std::vector<double> edges{ri};
    double size = growth == 1.0 ? (ro - ri) / radial
                                : (ro - ri) * (growth - 1) / (std::pow(growth, radial) - 1);
    for (int m = 0; m < radial; ++m, size *= growth) edges.push_back(edges.back() + size);
    edges.back() = ro;
    const int m = doubled_index / 2;
    return doubled_index % 2 == 0 ? edges[m] : (edges[m] + edges[m + 1]) / 2;
  }

  /// The axisymmetric (CAX) model instead of the sector.
  bool axisymmetric() const { return element_type.rfind("CAX", 0) == 0; }

  std::string deck() const {
    std::ostringstream out;
    out.precision(13);  // ccx reads numbers from 20-character fields
    if (axisymmetric()) {
      write_axisymmetric_mesh(out);
    } else {
      write_sector_mesh(out);
    }
    out << "*MATERIAL, NAME=STEEL\n*ELASTIC\n" << young << ", " << poisson << "\n";
    if (yield_stress > 0) out << "*PLASTIC\n" << yield_stress << ", 0.\n";
    if (density > 0) out << "*DENSITY\n" << density << "\n";
    out << "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n";
    const int axial_dof = axisymmetric() ? 2 : 3;
    out << "*BOUNDARY\n"
        << (axisymmetric() ? "" : "NALL, 2, 2\n") << (plane_strain ? "NALL" : "SUPPORT") << ", "
        << axial_dof << ", " << axial_dof << "\n";
    out << "*STEP" << (nlgeom ? ", NLGEOM" : "") << ", INC=1000" << step_options << "\n"
        << procedure << "\n"
        << increments << "\n";
    out << extra_step_cards;
    out << "*END STEP\n";
    return out.str();
  }

  void write_sector_mesh(std::ostringstream& out) const {
    const int ni = 2 * radial + 1, nj = 3, nk = 2 * axial + 1;
    const auto id = [&](int i, int j, int k) { return 1 + i + ni * (j + nj * k); };
    const auto exists = [](int i, int j, int k) { return (i % 2) + (j % 2) + (k % 2) <= 1; };
    out << "** Thick-walled cylinder: " << angle_degrees << " degree sector of " << element_type
        << "\n";
    out << "*NODE, NSET=NALL\n";
    for (int k = 0; k < nk; ++k)
      for (int j = 0; j < nj; ++j)
        for (int i = 0; i < ni; ++i) {
          if (!exists(i, j, k)) continue;
          const double theta = (centre_degrees + angle_degrees * (j - 1) / 2.0) * kPi / 180.0;
          const double r = radius(i);
          out << id(i, j, k) << ", " << r * std::cos(theta) << ", " << r * std::sin(theta) << ", "
              << length * k / (nk - 1) << "\n";
        }
    // C3D20 local nodes in natural coordinates (xi radial, eta hoop, zeta axial), 0..2.
    static const int local[20][3] = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {0, 0, 2},
                                     {2, 0, 2}, {2, 2, 2}, {0, 2, 2}, {1, 0, 0}, {2, 1, 0},
                                     {1, 2, 0}, {0, 1, 0}, {1, 0, 2}, {2, 1, 2}, {1, 2, 2},
                                     {0, 1, 2}, {0, 0, 1}, {2, 0, 1}, {2, 2, 1}, {0, 2, 1}};
    out << "*ELEMENT, TYPE=" << element_type << ", ELSET=EALL\n";
    std::vector<int> inner_elements;
    for (int q = 0; q < axial; ++q)
      for (int m = 0; m < radial; ++m) {
        const int element = 1 + m + radial * q;
        if (m == 0) inner_elements.push_back(element);
        out << element;
        for (int n = 0; n < 20; ++n) {
          out << (n == 15 ? ",\n" : ", ");  // ccx reads at most 16 entries a line
          out << id(2 * m + local[n][0], local[n][1], 2 * q + local[n][2]);
        }
        out << "\n";
      }
    out << "*NSET, NSET=INNERN\n";
    for (int k = 0; k < nk; ++k)
      for (int j = 0; j < nj; ++j)
        if (exists(0, j, k)) out << id(0, j, k) << ",\n";
    out << "*NSET, NSET=SUPPORT\n";
    for (int j = 0; j < nj; ++j) out << id(ni - 1, j, 0) << ",\n";
    out << "*SURFACE, NAME=INNER, TYPE=ELEMENT\n";  // r = ri is face S6 (xi = -1)
    for (const int element : inner_elements) out << element << ", S6\n";
    out << "*TRANSFORM, NSET=NALL, TYPE=C\n0., 0., 0., 0., 0., 1.\n";
  }

  void write_axisymmetric_mesh(std::ostringstream& out) const {
    const int ni = 2 * radial + 1, nk = 2 * axial + 1;
    const auto id = [&](int i, int k) { return 1 + i + ni * k; };
    out << "** Thick-walled cylinder: axisymmetric " << element_type << " (x radius, y axis)\n";
    out << "*NODE, NSET=NALL\n";
    for (int k = 0; k < nk; ++k)
      for (int i = 0; i < ni; ++i)
        if ((i % 2) + (k % 2) <= 1)
          out << id(i, k) << ", " << radius(i) << ", " << length * k / (nk - 1) << ", 0.\n";
    out << "*ELEMENT, TYPE=" << element_type << ", ELSET=EALL\n";
    for (int q = 0; q < axial; ++q)
      for (int m = 0; m < radial; ++m)
        out << 1 + m + radial * q << ", " << quad8_nodes(id, 2 * m, 2 * q) << "\n";
    out << "*NSET, NSET=INNERN\n";
    for (int k = 0; k < nk; ++k) out << id(0, k) << ",\n";
    out << "*NSET, NSET=SUPPORT\n" << id(ni - 1, 0) << ",\n";
    out << "*SURFACE, NAME=INNER, TYPE=ELEMENT\n";  // r = ri is the edge S4 (nodes 4-1)
    for (int q = 0; q < axial; ++q) out << 1 + radial * q << ", S4\n";
    // The end y = length (an annulus), for loads on radial edges: edge S3 (nodes 3-4).
    out << "*NSET, NSET=TOPN\n";
    for (int i = 0; i < ni; ++i) out << id(i, nk - 1) << ",\n";
    out << "*SURFACE, NAME=TOP, TYPE=ELEMENT\n";
    for (int m = 0; m < radial; ++m) out << 1 + m + radial * (axial - 1) << ", S3\n";
  }

  /// Lamé: radial displacement at radius r of the plane-strain cylinder under internal
  /// pressure p (elastic).
  double lame_radial_displacement(double p, double r) const {
    return p * ri * ri * (1 + poisson) / (young * (ro * ro - ri * ri)) *
           ((1 - 2 * poisson) * r + ro * ro / r);
  }

  /// Internal pressure at which the von Mises stress at r = ri reaches the yield stress
  /// (plane strain: sigma_z = nu (sigma_r + sigma_theta); all stresses scale with p).
  double yield_onset_pressure() const {
    const double a = ri * ri / (ro * ro - ri * ri);  // per unit pressure
    const double sigma_r = -1.0;
    const double sigma_theta = a * (1 + ro * ro / (ri * ri));
    const double sigma_z = poisson * (sigma_r + sigma_theta);
    const double von_mises = std::sqrt(0.5 * ((sigma_r - sigma_theta) * (sigma_r - sigma_theta) +
                                              (sigma_theta - sigma_z) * (sigma_theta - sigma_z) +
                                              (sigma_z - sigma_r) * (sigma_z - sigma_r)));
    return yield_stress / von_mises;
  }

  /// Area of the inner surface: of the sector, or of the whole bore (axisymmetric).
  double inner_area() const {
    return ri * (axisymmetric() ? 2 * kPi : angle_degrees * kPi / 180.0) * length;
  }
};

struct PlaneStrainStrip {
  double lx = 0.4;
  double ly = 0.1;
  double thickness = 0.5;
  int nx = 4;
  int ny = 2;
  double young = 200e9;
  double poisson = 0.3;
  std::string extra_step_cards;

  std::string deck() const {
    const int ni = 2 * nx + 1, nj = 2 * ny + 1;
    const auto id = [&](int i, int j) { return 1 + i + ni * j; };
    std::ostringstream out;
    out.precision(13);  // ccx reads numbers from 20-character fields
    out << "*NODE, NSET=NALL\n";
    for (int j = 0; j < nj; ++j)
      for (int i = 0; i < ni; ++i)
        if (i % 2 == 0 || j % 2 == 0)
          out << id(i, j) << ", " << lx * i / (ni - 1) << ", " << ly * j / (nj - 1) << "\n";
    out << "*ELEMENT, TYPE=CPE8, ELSET=EALL\n";
    for (int n = 0; n < ny; ++n)
      for (int m = 0; m < nx; ++m)
        out << 1 + m + nx * n << ", " << quad8_nodes(id, 2 * m, 2 * n) << "\n";
    out << "*NSET, NSET=TOPN\n";
    for (int i = 0; i < ni; ++i) out << id(i, nj - 1) << ",\n";
    out << "*NSET, NSET=BOTTOM\n";
    for (int i = 0; i < ni; ++i) out << id(i, 0) << ",\n";
    out << "*SURFACE, NAME=TOP, TYPE=ELEMENT\n";  // y = Ly is face S3 (nodes 3-4)
    for (int m = 0; m < nx; ++m) out << 1 + m + nx * (ny - 1) << ", S3\n";
    out << "*MATERIAL, NAME=STEEL\n*ELASTIC\n" << young << ", " << poisson << "\n";
    out << "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n" << thickness << "\n";
    out << "*BOUNDARY\nBOTTOM, 2, 2\n" << id(0, 0) << ", 1, 1\n";
    out << "*STEP\n*STATIC\n" << extra_step_cards << "*END STEP\n";
    return out.str();
  }
};

}  // namespace cocopp::testing

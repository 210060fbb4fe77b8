// ccx's SOLVER=SUITESPARSE (scripts/calculix/06-suitesparse-solver.patch) at its interface, on
// small matrices in ccx's storage against a dense LU: the symmetric positive definite matrix
// (CHOLMOD), a symmetric indefinite one (CHOLMOD refuses it, UMFPACK solves it), the two
// unsymmetric storages ccx hands its solvers (UMFPACK), the shifted matrix K - sigma M, and the
// analysis kept for a matrix of the same pattern and dropped for another. An unsymmetric matrix
// comes from ccx only with friction contact, which no deck of the wrapper's tests has: this is
// where its storage is checked. Linked with ccx's objects (libccx_cocopp.a).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

extern "C" {
void suitesparse_factor(double* ad, double* au, double* adb, double* aub, double* sigma, int* icol,
                        int* irow, int* neq, int* nzs, int* symmetryflag, int* inputformat,
                        int* nzs3);
void suitesparse_solve(double* b, int* neq);
void suitesparse_cleanup();
}

namespace {

/// A matrix in ccx's storage: the diagonal in ad; the off-diagonal entries column by column in
/// au (icol[j] of them in column j, their 1-based rows in irow). Symmetric (inputformat 0): the
/// lower triangle. Inputformat 1: the lower triangle, then from au[nzs] on the upper one at the
/// transposed positions. Inputformat 3: any off-diagonal entries.
struct CcxMatrix {
  int n = 0;
  int inputformat = 0;
  std::vector<double> ad, au;
  std::vector<int> icol, irow;
  Eigen::MatrixXd dense;

  int nzs() const { return static_cast<int>(irow.size()); }
};

/// A band-and-scatter pattern of order n: entry (i, j), i > j, where i - j is 1 or 7 or
/// (i * j) % 5 == 1; `seed` picks the values, diagonally dominant (signs of the diagonal from
/// `diagonal_sign`), so that every matrix is regular.
CcxMatrix make_matrix(int n, int inputformat, unsigned seed, double (*diagonal_sign)(int)) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  CcxMatrix m;
  m.n = n;
  m.inputformat = inputformat;
  m.dense = Eigen::MatrixXd::Zero(n, n);
  m.icol.assign(n, 0);
  std::vector<double> upper;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      if (i == j) continue;
      const int lo = std::min(i, j), hi = std::max(i, j);
      const bool in_pattern = hi - lo == 1 || hi - lo == 7 || (hi * lo) % 5 == 1;
      if (!in_pattern) continue;
      if (inputformat == 3) {
        // Structurally unsymmetric: drop every third entry above the diagonal.
        if (i < j && (i + j) % 3 == 0) continue;
        const double a = value(random);
        m.au.push_back(a);
        m.irow.push_back(i + 1);
        ++m.icol[j];
        m.dense(i, j) = a;
      } else if (i > j) {
        const double a = value(random);
        m.au.push_back(a);
        m.irow.push_back(i + 1);
        ++m.icol[j];
        m.dense(i, j) = a;
        const double b = inputformat == 1 ? value(random) : a;
        upper.push_back(b);
        m.dense(j, i) = b;
      }
    }
  }
  if (inputformat == 1) m.au.insert(m.au.end(), upper.begin(), upper.end());
  m.ad.resize(n);
  for (int i = 0; i < n; ++i) {
    const double off = m.dense.row(i).cwiseAbs().sum() + m.dense.col(i).cwiseAbs().sum();
    m.ad[i] = diagonal_sign(i) * (off + 1.0 + value(random) * 0.1);
    m.dense(i, i) = m.ad[i];
  }
  return m;
}

double positive(int) {
  return 1.0;
}
double mixed(int i) {
  return i % 3 == 0 ? -1.0 : 1.0;
}

/// The largest difference between SuiteSparse's solutions of m x = b for `rhs` right-hand
/// sides and the dense LU's, relative to the largest component; factor once, solve each.
double solve_difference(CcxMatrix& m, int rhs = 2, double sigma = 0.0, CcxMatrix* mass = nullptr) {
  int symmetryflag = m.inputformat == 0 ? 0 : 2, nzs = m.nzs(), nzs3 = nzs;
  Eigen::MatrixXd a = m.dense;
  if (mass != nullptr) a -= sigma * mass->dense;
  suitesparse_factor(m.ad.data(), m.au.data(), mass ? mass->ad.data() : nullptr,
                     mass ? mass->au.data() : nullptr, &sigma, m.icol.data(), m.irow.data(), &m.n,
                     &nzs, &symmetryflag, &m.inputformat, &nzs3);
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(a);
  double worst = 0.0;
  for (int k = 0; k < rhs; ++k) {
    Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(m.n, 1.0, 2.0 + k).array().sin();
    const Eigen::VectorXd expected = lu.solve(b);
    suitesparse_solve(b.data(), &m.n);
    worst = std::max(worst, (b - expected).cwiseAbs().maxCoeff() / expected.cwiseAbs().maxCoeff());
  }
  suitesparse_cleanup();
  return worst;
}

// Round-off of a well-conditioned system of order 40 (dominant diagonal): far below this.
constexpr double kTolerance = 1e-12;

/// What the solver prints (ccx's style: which solver factors) while `run` runs.
template <class Run>
std::string printed(Run run) {
  ::testing::internal::CaptureStdout();
  run();
  std::fflush(stdout);
  return ::testing::internal::GetCapturedStdout();
}

TEST(CcxSuiteSparse, SymmetricPositiveDefiniteByCholmod) {
  CcxMatrix m = make_matrix(40, 0, 1, positive);
  const std::string log = printed([&] { EXPECT_LT(solve_difference(m), kTolerance); });
  EXPECT_NE(log.find("symmetric SuiteSparse (CHOLMOD)"), std::string::npos) << log;
  EXPECT_EQ(log.find("UMFPACK"), std::string::npos) << log;
}

TEST(CcxSuiteSparse, SymmetricIndefiniteByUmfpack) {
  // CHOLMOD's LL' stops at the first negative pivot; UMFPACK pivots, as SPOOLES does.
  CcxMatrix m = make_matrix(40, 0, 2, mixed);
  const std::string log = printed([&] { EXPECT_LT(solve_difference(m), kTolerance); });
  EXPECT_NE(log.find("not positive definite: factoring it with SuiteSparse's UMFPACK"),
            std::string::npos)
      << log;
}

TEST(CcxSuiteSparse, UnsymmetricValuesOnASymmetricPattern) {
  CcxMatrix m = make_matrix(40, 1, 3, mixed);
  EXPECT_LT(solve_difference(m), kTolerance);
}

TEST(CcxSuiteSparse, StructurallyUnsymmetric) {
  CcxMatrix m = make_matrix(40, 3, 4, positive);
  EXPECT_LT(solve_difference(m), kTolerance);
}

TEST(CcxSuiteSparse, ShiftedByTheMassMatrix) {
  // K - sigma M with M of the same pattern (ccx's adb, aub): positive definite for a small
  // sigma, indefinite for a large one.
  CcxMatrix k = make_matrix(40, 0, 5, positive);
  CcxMatrix mass = make_matrix(40, 0, 6, positive);
  EXPECT_LT(solve_difference(k, 1, 0.1, &mass), kTolerance);
  EXPECT_LT(solve_difference(k, 1, 3.0, &mass), kTolerance);
}

TEST(CcxSuiteSparse, AnalysisKeptForTheSamePatternOnly) {
  // The same pattern with other values (a Newton iteration's next matrix), then another pattern
  // and order, then the first again, and an unsymmetric one in between: each solved exactly.
  for (int round = 0; round < 2; ++round) {
    for (unsigned seed : {10U, 11U, 12U}) {
      CcxMatrix m = make_matrix(40, 0, seed + 10 * round, positive);
      EXPECT_LT(solve_difference(m, 1), kTolerance) << seed;
    }
    CcxMatrix other = make_matrix(33, 0, 20 + round, positive);
    EXPECT_LT(solve_difference(other, 1), kTolerance);
    CcxMatrix unsymmetric = make_matrix(40, 1, 30 + round, positive);
    EXPECT_LT(solve_difference(unsymmetric, 1), kTolerance);
    CcxMatrix again = make_matrix(40, 1, 40 + round, mixed);
    EXPECT_LT(solve_difference(again, 1), kTolerance);
  }
}

}  // namespace

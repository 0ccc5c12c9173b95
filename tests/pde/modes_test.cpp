// The per-mode maths: the paper's errata, the stable basis, the series basis for small m, the cardinal
// functions against a 50-digit reference, the amplification of four-position patches, the cosine transform.

#include "pdeface/pde/modes.hpp"

#include "pdeface_test.hpp"

#include <Eigen/LU>

#include <cmath>
#include <numbers>
#include <sstream>

namespace {

using namespace pdeface::pde;

// The paper's d (below its equation 8), as printed.
double paper_d(double n) { return std::exp(4 * n) - 4 * n * n * std::exp(2 * n) - 2 * std::exp(2 * n) + 1; }

// The paper's basis e^{nu}, u e^{nu}, e^{−nu}, u e^{−nu} (equation 4) at u, derivative 0 or 1.
Eigen::RowVector4d paper_basis(double n, double u, int derivative) {
  const double ep = std::exp(n * u), em = std::exp(-n * u);
  if (derivative == 0) return {ep, u * ep, em, u * em};
  return {n * ep, (1 + n * u) * ep, -n * em, (1 - n * u) * em};
}

const double ns[] = {0.5, 1, 2, 3, 5, 10, 20, 50, 100, 150, 177, 178, 300, 500, 709, 710, 1000};

TEST(PdeErrata, PaperDIsThePositionDerivativeDeterminant) {
  for (double n : {0.5, 1.0, 2.0, 5.0, 10.0, 20.0}) { // the paper's own basis, while it is representable
    Eigen::Matrix4d pd, p4;
    pd << paper_basis(n, 0, 0), paper_basis(n, 0, 1), paper_basis(n, 1, 0), paper_basis(n, 1, 1);
    p4 << paper_basis(n, 0, 0), paper_basis(n, 1.0 / 3, 0), paper_basis(n, 2.0 / 3, 0), paper_basis(n, 1, 0);
    EXPECT_NEAR(std::exp(2 * n) * pd.determinant() / paper_d(n), 1, 1e-12) << n;
    const double sinh3 = std::sinh(n / 3);
    EXPECT_NEAR(p4.determinant() / (16.0 / 9 * std::pow(sinh3, 4)), 1, 1e-11) << n;
    // ...so d is not the determinant of the four-position system the paper says it solves.
    EXPECT_GT(std::abs(std::exp(2 * n) * p4.determinant() / paper_d(n) - 1), 0.5) << n;
  }
}

TEST(PdeErrata, StableDeterminantsMatchTheClosedForms) {
  for (double n : ns) {
    // det of the stable basis = −n² e^{−2n} · det of the paper's basis (a change of basis).
    const double pd = position_derivative_matrix(n).determinant();
    const double q = std::exp(-2 * n);
    EXPECT_NEAR(pd / (-n * n * (1 - (4 * n * n + 2) * q + q * q)), 1, 1e-12) << n;
    if (std::isfinite(std::exp(4 * n) * n * n)) {
      EXPECT_NEAR(-std::exp(4 * n) * pd / (n * n) / paper_d(n), 1, 1e-12) << n;
    }
    const double p4 = four_position_matrix(n, 1.0 / 3, 2.0 / 3).determinant();
    const double r = std::exp(-2 * n / 3); // −n² e^{−2n} (16/9) sinh⁴(n/3), without overflow
    EXPECT_NEAR(p4 / (-n * n / 9 * r * std::pow(1 - r, 4)), 1, 1e-12) << n;
  }
}

TEST(PdeErrata, PaperClosedFormOverflowsFromN177) {
  EXPECT_TRUE(std::isfinite(paper_d(176)));
  EXPECT_FALSE(std::isfinite(paper_d(178))); // e^{4n} overflows: c1..c4 become inf/inf = NaN
  for (double n : ns)
    for (double t : {0.0, 0.3, 1.0})
      for (int derivative = 0; derivative <= 2; ++derivative)
        EXPECT_TRUE(hermite_cardinals(n, t, derivative).allFinite()) << n;
}

TEST(PdeModes, NothingOverflowsUpToN1000) {
  for (double n = 0; n <= 1000; n += 0.5) {
    for (double t : {0.0, 1e-3, 0.25, 0.5, 0.999, 1.0}) {
      ASSERT_TRUE(hermite_cardinals(n, t, 0).allFinite()) << n << " " << t;
      if (n > 0) {
        ASSERT_TRUE(stable_basis(n, t, 2).allFinite()) << n;
      }
    }
    ASSERT_FALSE(std::isnan(four_position_amplification(n, 1.0 / 3, 2.0 / 3))) << n;
  }
}

TEST(PdeModes, StableBasisSolvesTheModeEquation) {
  // A'''' − 2m²A'' + m⁴A = 0 with A'''' by differences of the second derivative.
  for (double m : {0.5, 3.0, 40.0}) {
    const double t = 0.4, h = 1e-3;
    const Eigen::Vector4d a2 = stable_basis(m, t, 2);
    const Eigen::Vector4d a4 = (stable_basis(m, t + h, 2) - 2 * a2 + stable_basis(m, t - h, 2)) / (h * h);
    const Eigen::Vector4d residual = a4 - 2 * m * m * a2 + std::pow(m, 4) * stable_basis(m, t);
    EXPECT_LT(residual.cwiseAbs().maxCoeff(), 1e-5 * (a4.cwiseAbs().maxCoeff() + std::pow(m, 4))) << m;
  }
}

TEST(PdeModes, HermiteCardinalsMatchA50DigitReference) {
  int rows = 0;
  double worst = 0;
  for (const std::string& line : pdeface::test::fixture_rows("pde", "hermite_cardinals.txt")) {
    std::istringstream s(line);
    double m = 0, t = 0;
    int derivative = 0;
    Eigen::Vector4d expected;
    s >> m >> t >> derivative >> expected[0] >> expected[1] >> expected[2] >> expected[3];
    ASSERT_TRUE(s) << line;
    const Eigen::Vector4d got = hermite_cardinals(m, t, derivative);
    for (int i = 0; i < 4; ++i) {
      const double error = std::abs(got[i] - expected[i]) / std::max(1.0, std::abs(expected[i]));
      worst = std::max(worst, error);
      EXPECT_LT(error, 1e-13) << line << " component " << i << " got " << got[i];
    }
    ++rows;
  }
  EXPECT_EQ(rows, 11 * 6 * 3);
  std::printf("hermite cardinals: worst relative error %.2e over %d rows\n", worst, rows);
}

TEST(PdeModes, CubicLimitAndEndCurvatures) {
  // m → 0 is the cubic Hermite spline: a''(0) = −6 p0 − 4 d0 + 6 p1 − 2 d1 (method.md's limits).
  EXPECT_TRUE(hermite_cardinals(0, 0, 2).isApprox(Eigen::Vector4d(-6, -4, 6, -2), 1e-14));
  EXPECT_TRUE(hermite_cardinals(1e-8, 0, 2).isApprox(Eigen::Vector4d(-6, -4, 6, -2), 1e-12));
  // method.md's closed forms for a''(0) (P, Dd, Q, G) and a''(1) = (Q, −G, P, −Dd), where they are safe.
  for (double m : {1.0, 2.0, 7.0, 50.0, 700.0}) {
    const double q = std::exp(-m), q2 = q * q;
    const double delta = (1 - q2) * (1 - q2) - 4 * m * m * q2;
    const double p = -m * m * ((1 - q2) * (1 - q2) + 4 * m * m * q2) / delta;
    const double dd = -2 * m * (1 - q2 * q2 - 4 * m * q2) / delta;
    const double qq = 4 * m * m * m * q * (1 - q2) / delta;
    const double g = 4 * m * q * ((1 - q2) - m * (1 + q2)) / delta;
    EXPECT_TRUE(hermite_cardinals(m, 0, 2).isApprox(Eigen::Vector4d(p, dd, qq, g), 1e-12)) << m;
    EXPECT_TRUE(hermite_cardinals(m, 1, 2).isApprox(Eigen::Vector4d(qq, -g, p, -dd), 1e-12)) << m;
  }
}

TEST(PdeModes, Patch4AmplificationMatchesTheReference) {
  int rows = 0;
  for (const std::string& line : pdeface::test::fixture_rows("pde", "patch4_amplification.txt")) {
    std::istringstream s(line);
    double m = 0, expected = 0;
    s >> m >> expected;
    const double got = four_position_amplification(m, 1.0 / 3, 2.0 / 3);
    if (m < 1) {
      // leb.py's stable-basis solve has a condition number of 1.7e11 at m = 0.001 and is off by 3e-6;
      // the value is within O(m²) of the cubic's (below).
      EXPECT_NEAR(got, 1.6311303094, 1e-8);
      EXPECT_NEAR(got, expected, 1e-5);
    } else { // leb.py samples 20001 points; the refined maximum can only be as large or a little larger
      EXPECT_GE(got, expected * (1 - 1e-9)) << m;
      EXPECT_LE(got, expected * (1 + 1e-5)) << m;
    }
    ++rows;
  }
  EXPECT_EQ(rows, 15);
  // m = 0: the Lebesgue constant of cubic interpolation at equispaced nodes.
  EXPECT_NEAR(four_position_amplification(0, 1.0 / 3, 2.0 / 3), 1.6311303094, 1e-10);
  // The figures method.md quotes, and the asymptote e^{m/3 − 1}/(m/3).
  EXPECT_NEAR(four_position_amplification(20, 1.0 / 3, 2.0 / 3), 43.8, 0.1);
  EXPECT_NEAR(four_position_amplification(60, 1.0 / 3, 2.0 / 3), 8.92e6, 0.01e6);
  EXPECT_NEAR(four_position_amplification(100, 1.0 / 3, 2.0 / 3) / (std::exp(100.0 / 3 - 1) / (100.0 / 3)), 1,
              1e-3);
  // A singular system (every inner value underflows) amplifies without bound.
  EXPECT_TRUE(std::isinf(four_position_amplification(5000, 1.0 / 3, 2.0 / 3)));
}

TEST(PdeModes, CosineCoefficientsInterpolateEverySample) {
  for (Eigen::Index count : {2, 3, 15, 30, 301}) {
    const Eigen::MatrixXd samples = Eigen::MatrixXd::Random(count, 5);
    const Eigen::MatrixXd alpha = cosine_coefficients(samples);
    Eigen::MatrixXd cosines(count, count);
    for (Eigen::Index k = 0; k < count; ++k)
      for (Eigen::Index n = 0; n < count; ++n)
        cosines(k, n) =
            std::cos(static_cast<double>(n * k) * std::numbers::pi / static_cast<double>(count - 1));
    EXPECT_LT((cosines * alpha - samples).cwiseAbs().maxCoeff(), 1e-13) << count;
  }
  // One pure cosine, including the last one (alternating signs), is one coefficient.
  const Eigen::Index count = 9;
  for (Eigen::Index n = 0; n < count; ++n) {
    Eigen::MatrixXd samples(count, 1);
    for (Eigen::Index k = 0; k < count; ++k)
      samples(k, 0) =
          std::cos(static_cast<double>(n * k) * std::numbers::pi / static_cast<double>(count - 1));
    Eigen::VectorXd expected = Eigen::VectorXd::Zero(count);
    expected[n] = 1;
    EXPECT_LT((cosine_coefficients(samples).col(0) - expected).cwiseAbs().maxCoeff(), 1e-14) << n;
  }
  EXPECT_THROW((void)cosine_coefficients(Eigen::MatrixXd(1, 3)), std::invalid_argument);
}

TEST(PdeModes, BadCallsThrow) {
  EXPECT_THROW((void)stable_basis(0, 0.5), std::invalid_argument);
  EXPECT_THROW((void)stable_basis(1, 0.5, 3), std::invalid_argument);
  EXPECT_THROW((void)hermite_cardinals(1, 0.5, -1), std::invalid_argument);
}

} // namespace

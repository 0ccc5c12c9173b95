// The surface through the curves: interpolation, the PDE itself, smoothness at the joints, amplification,
// refusal of patch4 beyond its cap, errors for bad curves and options, evaluation and meshing.

#include "pdeface/pde/surface.hpp"

#include "pdeface_test.hpp"
#include "synthetic_face.hpp"

#include <numbers>
#include <sstream>

namespace {

using namespace pdeface;
using namespace pdeface::pde;

const double a_paper_iso = std::numbers::pi * 15 / 180; // face_run3.py's isotropic a for the synthetic face

Surface build(const Curves& curves, const Options& options) {
  auto s = Surface::build(curves, options);
  if (!s) throw std::runtime_error(s.error().to_string());
  return std::move(s).value();
}

std::vector<double> sample_vs(std::size_t count) { return face::linspace(0, std::numbers::pi, count); }

// Largest |X(U_j, v_k) − P_j(v_k)| over the chosen curves, relative to the largest coordinate.
double curve_error(const Surface& s, const Curves& curves, const std::vector<std::size_t>& which) {
  std::vector<double> us;
  for (std::size_t j : which)
    us.push_back(s.knots()[j]);
  const Grid grid = s.evaluate(us, sample_vs(s.sample_count()));
  double worst = 0, scale = 0;
  for (std::size_t c = 0; c < which.size(); ++c)
    for (std::size_t k = 0; k < grid.v_count; ++k) {
      const Vec3 p = curves.samples[which[c]].row(static_cast<Eigen::Index>(k)).transpose();
      worst = std::max(worst, (grid(c, k) - p).cwiseAbs().maxCoeff());
      scale = std::max(scale, p.cwiseAbs().maxCoeff());
    }
  return worst / scale;
}

std::vector<std::size_t> all_curves(std::size_t count) {
  std::vector<std::size_t> j(count);
  for (std::size_t i = 0; i < count; ++i)
    j[i] = i;
  return j;
}

TEST(PdeSurface, SplineInterpolatesEveryCurveAtEverySample) {
  double worst = 0;
  for (std::size_t samples : {15u, 60u, 181u}) {
    const Curves curves = face::profiles(samples);
    for (std::size_t modes : {samples - 1, std::size_t{5}, std::size_t{12}})
      for (double a : {1.0, a_paper_iso}) {
        const Surface s = build(curves, {.smoothing = a, .modes = modes});
        EXPECT_EQ(s.has_remainder(), modes < samples - 1);
        const double error = curve_error(s, curves, all_curves(curves.samples.size()));
        EXPECT_LE(error, 1e-9) << samples << " samples, " << modes << " modes, a = " << a;
        worst = std::max(worst, error);
      }
  }
  std::printf("spline: worst relative curve error %.2e\n", worst);
}

TEST(PdeSurface, WithoutTheRemainderFewerModesMissTheCurves) {
  const Curves curves = face::profiles(60);
  const Surface truncated = build(curves, {.modes = 10, .remainder = false});
  EXPECT_FALSE(truncated.has_remainder());
  EXPECT_GT(curve_error(truncated, curves, all_curves(28)), 1e-3);
}

TEST(PdeSurface, Patch4InterpolatesEveryCurveWithinItsCap) {
  const Curves curves = face::profiles(60);
  for (std::size_t modes : {std::size_t{20}, std::size_t{40}}) {
    const Surface s = build(curves, {.scheme = Scheme::Patch4, .smoothing = a_paper_iso, .modes = modes});
    EXPECT_LE(curve_error(s, curves, all_curves(28)), 1e-9) << modes;
  }
}

TEST(PdeSurface, PaperInterpolatesOnlyThePatchEnds) {
  const Curves curves = face::profiles(60);
  for (std::size_t modes : {std::size_t{59}, std::size_t{10}}) {
    const Surface s = build(curves, {.scheme = Scheme::Paper, .smoothing = 1.0, .modes = modes});
    std::vector<std::size_t> ends, inner;
    for (std::size_t j = 0; j < 28; ++j)
      (j % 3 == 0 ? ends : inner).push_back(j);
    EXPECT_LE(curve_error(s, curves, ends), 1e-9) << modes;
    EXPECT_GT(curve_error(s, curves, inner), 1e-3) << modes; // the inner curves only give slopes
  }
}

TEST(PdeSurface, PhysicalSpacingFollowsTheCurvesMeanX) {
  Curves curves = face::profiles(30);
  std::vector<double> xs;
  for (std::size_t j = 0; j < 28; ++j) { // uneven spacing, denser in the middle
    const double s = static_cast<double>(j) / 27 * 2 - 1;
    xs.push_back(67.5 * (0.4 * s + 0.6 * s * s * s));
    curves.samples[j].col(0).setConstant(xs.back());
  }
  const Surface s = build(curves, {.spacing = Spacing::Physical});
  ASSERT_EQ(s.knots().size(), 28u);
  EXPECT_EQ(s.knots().front(), 0);
  EXPECT_EQ(s.u_max(), 9);
  for (std::size_t j = 0; j < 28; ++j)
    EXPECT_NEAR(s.knots()[j], 9 * (xs[j] - xs[0]) / (xs[27] - xs[0]), 1e-12);
  EXPECT_LE(curve_error(s, curves, all_curves(28)), 1e-9);
  // Every scheme reproduces x, which is linear in u here, exactly between the curves too (linear precision:
  // the paper's slopes must be scaled to patches of any length).
  for (Scheme scheme : {Scheme::Spline, Scheme::Paper, Scheme::Patch4}) {
    const Surface t = build(curves, {.scheme = scheme, .modes = 8, .spacing = Spacing::Physical});
    const Grid g = t.evaluate(face::linspace(0, 9, 200), face::linspace(0, std::numbers::pi, 9));
    for (std::size_t i = 0; i < g.u_count; ++i)
      for (std::size_t k = 0; k < g.v_count; ++k)
        ASSERT_NEAR(g(i, k).x(), xs[0] + (xs[27] - xs[0]) * static_cast<double>(i) / 199, 1e-9)
            << to_string(scheme);
  }
  // Reversed order (decreasing x) is accepted as well.
  std::reverse(curves.samples.begin(), curves.samples.end());
  EXPECT_TRUE(Surface::build(curves, {.spacing = Spacing::Physical}).ok());
}

// (∂²/∂u² + a²∂²/∂v²)² X by differences on a 5 × 5 stencil with steps δ in u and a·δ in v (so the operator
// is the plain biharmonic one in u and w = v/a), extrapolated from δ and δ/2 (Richardson: the O(δ²) error
// of the differences cancels): the residual against the size of its three terms.
double pde_residual(const Surface& s, double u0, double v0, double delta) {
  const double a = s.smoothing();
  const auto terms = [&](double d) {
    std::vector<double> us, vs;
    for (int i = -2; i <= 2; ++i)
      us.push_back(u0 + i * d), vs.push_back(v0 + i * a * d);
    const Grid g = s.evaluate(us, vs);
    const auto x = [&](int i, int k) {
      return g(static_cast<std::size_t>(i + 2), static_cast<std::size_t>(k + 2));
    };
    const double d4 = std::pow(d, 4);
    Eigen::Matrix3d t; // columns: X_uuuu, 2 X_uuww, X_wwww
    t.col(0) = (x(-2, 0) - 4 * x(-1, 0) + 6 * x(0, 0) - 4 * x(1, 0) + x(2, 0)) / d4;
    t.col(2) = (x(0, -2) - 4 * x(0, -1) + 6 * x(0, 0) - 4 * x(0, 1) + x(0, 2)) / d4;
    t.col(1).setZero();
    for (int i = -1; i <= 1; ++i)
      for (int k = -1; k <= 1; ++k)
        t.col(1) += 2 * (i == 0 ? -2.0 : 1.0) * (k == 0 ? -2.0 : 1.0) * x(i, k) / d4;
    return t;
  };
  const Eigen::Matrix3d t = (4 * terms(delta / 2) - terms(delta)) / 3;
  return t.rowwise().sum().norm() / t.colwise().norm().sum();
}

TEST(PdeSurface, SolvesThePdeInsideEveryPiece) {
  const Curves curves = face::profiles(60);
  double worst = 0;
  for (Scheme scheme : {Scheme::Spline, Scheme::Paper, Scheme::Patch4})
    for (double a : {1.0, a_paper_iso}) {
      // 20 modes, each solved exactly (no remainder: R is not a solution of the PDE); steps δ = 0.005/a
      // resolve e^{−a n u} for n ≤ 20 (δ·a·n = 0.1) and keep rounding small.
      const Surface s = build(curves, {.scheme = scheme,
                                       .smoothing = a,
                                       .modes = 20,
                                       .remainder = false,
                                       .patch4_max_amplification = 100});
      for (double u0 : {0.5, 4.4, 8.2})
        for (double v0 : {0.9, 2.0}) {
          const double residual = pde_residual(s, u0, v0, 0.005 / a);
          worst = std::max(worst, residual);
          EXPECT_LT(residual, 1e-4) << to_string(scheme) << " a = " << a << " at " << u0 << ", " << v0;
        }
    }
  std::printf("pde residual: at most %.1e of its terms\n", worst);
}

// Largest angle (degrees) between the u-tangents on either side of the given joints, over the samples.
double worst_kink(const Surface& s, const std::vector<double>& joints) {
  double worst = 0;
  const std::vector<double> vs = sample_vs(s.sample_count());
  for (double u : joints) {
    const Grid left = s.evaluate(std::vector<double>{u - 1e-12}, vs, Derivative::U);
    const Grid right = s.evaluate(std::vector<double>{u}, vs, Derivative::U);
    for (std::size_t k = 0; k < vs.size(); ++k) {
      const double c = left(0, k).dot(right(0, k)) / (left(0, k).norm() * right(0, k).norm());
      worst = std::max(worst, std::acos(std::clamp(c, -1.0, 1.0)) * 180 / std::numbers::pi);
    }
  }
  return worst;
}

TEST(PdeSurface, SplineJointsAreSmoothPaperJointsKink) {
  int rows = 0;
  for (const std::string& line : pdeface::test::fixture_rows("pde", "paper_kinks.txt")) {
    std::istringstream fields(line);
    double ratio = 0, a = 0, expected = 0;
    std::size_t modes = 0;
    int remainder = 0;
    fields >> ratio >> a >> modes >> remainder >> expected;
    const Curves curves = face::profiles(60);
    const Options options{.smoothing = a, .modes = modes, .remainder = remainder != 0};
    Options paper = options, patch4 = options;
    paper.scheme = Scheme::Paper;
    patch4.scheme = Scheme::Patch4;
    patch4.patch4_max_amplification = 1e7;
    const std::vector<double> patch_joints{1, 2, 3, 4, 5, 6, 7, 8};
    const Surface spline = build(curves, options);
    const std::vector<double> knots(spline.knots().begin() + 1, spline.knots().end() - 1);
    const double spline_kink = worst_kink(spline, knots),
                 paper_kink = worst_kink(build(curves, paper), patch_joints);
    const double patch4_kink = worst_kink(build(curves, patch4), patch_joints);
    EXPECT_LT(spline_kink, 1e-3) << line; // C¹ by construction: only rounding
    EXPECT_NEAR(paper_kink, expected, 1e-4) << line;
    EXPECT_GT(patch4_kink, 10) << line;
    std::printf("joints (a = %.3f, N = %zu, R = %d): spline %.1e deg, paper %.2f deg, patch4 %.1f deg\n", a,
                modes, remainder, spline_kink, paper_kink, patch4_kink);
    ++rows;
  }
  EXPECT_EQ(rows, 3);
}

TEST(PdeSurface, SplineAmplificationIsAtMost155ForEveryMode) {
  int rows = 0;
  for (const std::string& line : pdeface::test::fixture_rows("pde", "spline_amplification.txt")) {
    std::istringstream fields(line);
    std::size_t n = 0;
    double expected = 0;
    fields >> n >> expected;
    // Curves whose only content is mode n: curve j carries δ_ij cos(n v) in one coordinate, so X(u, 0)
    // is the spline's Lagrange function of curve i. Three per surface, one per coordinate.
    const std::size_t samples = std::max<std::size_t>(n + 1, 2);
    const std::vector<double> us = face::linspace(0, 9, 9 * 60 + 1);
    std::vector<double> lebesgue(us.size(), 0.0);
    for (std::size_t first = 0; first < 28; first += 3) {
      Curves curves;
      curves.samples.assign(28, Curve::Zero(static_cast<Eigen::Index>(samples), 3));
      for (std::size_t c = 0; c < 3 && first + c < 28; ++c)
        for (std::size_t k = 0; k < samples; ++k)
          curves.samples[first + c](static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(c)) =
              std::cos(static_cast<double>(n * k) * std::numbers::pi / static_cast<double>(samples - 1));
      const Grid g = build(curves, {.smoothing = 1.0, .modes = n}).evaluate(us, std::vector<double>{0.0});
      for (std::size_t i = 0; i < us.size(); ++i)
        lebesgue[i] += g(i, 0).cwiseAbs().sum();
    }
    const double got = *std::max_element(lebesgue.begin(), lebesgue.end());
    EXPECT_LE(got, 1.55) << n;
    EXPECT_NEAR(got, expected, 2e-3) << n; // spline_leb.py samples 10× more densely
    ++rows;
  }
  EXPECT_EQ(rows, 11);
}

TEST(PdeSurface, Patch4IsRefusedBeyondItsCap) {
  const Curves curves = face::profiles(60);
  const auto refused = Surface::build(curves, {.scheme = Scheme::Patch4, .smoothing = 1.0}, "face.pdef");
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().code, ErrorCode::InvalidArgument);
  EXPECT_EQ(refused.error().source, "face.pdef");
  const std::string& message = refused.error().message;
  EXPECT_NE(message.find("patch4 would amplify the curves' data 6.5e+06-fold at frequency 59"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("highest stable frequency is 14, so use at most 13 modes with the remainder"),
            std::string::npos)
      << message;
  // Exactly at the edge the message names: frequency 14 (amplification 8.5) is in, 15 (11.4) is out.
  EXPECT_TRUE(Surface::build(curves, {.scheme = Scheme::Patch4, .smoothing = 1.0, .modes = 13}).ok());
  EXPECT_TRUE(
      Surface::build(curves, {.scheme = Scheme::Patch4, .smoothing = 1.0, .modes = 14, .remainder = false})
          .ok());
  EXPECT_FALSE(Surface::build(curves, {.scheme = Scheme::Patch4, .smoothing = 1.0, .modes = 14}).ok());
  // The cap is an option; an overflowing system is refused whatever the cap.
  EXPECT_TRUE(
      Surface::build(curves, {.scheme = Scheme::Patch4, .smoothing = 1.0, .patch4_max_amplification = 1e7}));
  const auto overflow = Surface::build(
      curves, {.scheme = Scheme::Patch4, .smoothing = 100.0, .patch4_max_amplification = INFINITY});
  ASSERT_FALSE(overflow.ok());
  EXPECT_NE(overflow.error().message.find("inf-fold"), std::string::npos) << overflow.error().message;
}

TEST(PdeSurface, MaxModesIsTheEdgeBuildAccepts) {
  const Curves curves = face::profiles(60);
  const Options patch4{.scheme = Scheme::Patch4, .smoothing = 1.0};
  EXPECT_EQ(max_modes(curves, patch4).value(), 13u); // with the remainder: frequency 14 is the last in
  Options without = patch4;
  without.remainder = false;
  EXPECT_EQ(max_modes(curves, without).value(), 14u);
  for (const Options& o : {patch4, without}) {
    Options at = o, beyond = o;
    at.modes = max_modes(curves, o).value();
    beyond.modes = *at.modes + 1;
    EXPECT_TRUE(Surface::build(curves, at).ok());
    EXPECT_FALSE(Surface::build(curves, beyond).ok());
  }
  // Every mode fits for the stable schemes, and for patch4 on short curves; nothing fits at a huge a.
  EXPECT_EQ(max_modes(curves, {.scheme = Scheme::Spline, .smoothing = 1.0}).value(), 59u);
  EXPECT_EQ(max_modes(curves, {.scheme = Scheme::Paper, .smoothing = 1.0}).value(), 59u);
  EXPECT_EQ(max_modes(face::profiles(12), patch4).value(), 11u);
  EXPECT_FALSE(max_modes(curves, {.scheme = Scheme::Patch4, .smoothing = 1000.0}).ok());
}

TEST(PdeSurface, NothingOverflowsUpToMode1000) {
  const Curves curves = face::profiles(1001);
  for (Scheme scheme : {Scheme::Spline, Scheme::Paper, Scheme::Patch4}) {
    // Patch4 at mode 1000 amplifies by ~1e142: useless, but finite.
    const auto s =
        Surface::build(curves, {.scheme = scheme, .smoothing = 1.0, .patch4_max_amplification = 1e300});
    ASSERT_TRUE(s.ok()) << s.error().to_string();
    for (Derivative d : {Derivative::None, Derivative::U, Derivative::V}) {
      const Grid g = s->evaluate(face::linspace(0, 9, 91), face::linspace(0, std::numbers::pi, 77), d);
      for (const Vec3& p : g.points)
        ASSERT_TRUE(p.allFinite()) << to_string(scheme);
    }
  }
}

TEST(PdeSurface, DefaultSmoothingIsIsotropic) {
  const Curves curves = face::profiles(60);
  const auto a = isotropic_smoothing(curves);
  ASSERT_TRUE(a.ok());
  // W = 16.51 mm of surface per unit u (5 mm between planes, plus the slope of the face), L = 189.4 mm.
  EXPECT_NEAR(*a, std::numbers::pi * 16.506333 / 189.381155, 1e-7);
  const Surface s = build(curves, {});
  EXPECT_EQ(s.smoothing(), *a);
  EXPECT_EQ(s.modes(), 59u);
  EXPECT_EQ(s.scheme(), Scheme::Spline);
  // As good as face_run3's a = π·15/180 on this face (5.17e-3 mm mean error), far better than a = 1.
  const double iso = face::surface_error(face::grid(s)).mean;
  const double paper = face::surface_error(face::grid(build(curves, {.smoothing = 1.0}))).mean;
  std::printf("spline, 60 samples, all modes: mean error %.3e mm at the default a = %.4f, %.3e mm at a = 1\n",
              iso, *a, paper);
  EXPECT_LT(iso, 6e-3);
  EXPECT_GT(paper, 10 * iso);
}

struct BadInput {
  std::string name;
  std::function<void(Curves&, Options&)> change;
  ErrorCode code;
  std::string message;
};

TEST(PdeSurface, BadCurvesAndOptionsAreErrors) {
  const std::vector<BadInput> cases{
      {"three curves", [](Curves& c, Options&) { c.samples.resize(3); }, ErrorCode::InvalidArgument,
       "need at least 4 curves, got 3"},
      {"no curves", [](Curves& c, Options&) { c.samples.clear(); }, ErrorCode::InvalidArgument,
       "need at least 4 curves, got 0"},
      {"one sample",
       [](Curves& c, Options&) {
         for (Curve& k : c.samples)
           k.conservativeResize(1, 3);
       },
       ErrorCode::InvalidArgument, "curve 0 has too few samples (1): need at least 2"},
      {"too many samples", [](Curves& c, Options&) { c.samples[3].conservativeResize(4098, 3); },
       ErrorCode::InvalidArgument, "curve 3 has 4098 samples: at most 4097 are supported"},
      {"sample counts differ", [](Curves& c, Options&) { c.samples[2].conservativeResize(9, 3); },
       ErrorCode::InvalidArgument,
       "curve 2 has 9 samples but curve 0 has 10: every curve needs the same number"},
      {"nan", [](Curves& c, Options&) { c.samples[1](3, 2) = NAN; }, ErrorCode::NonFinite,
       "curve 1, sample 3: coordinate is not finite"},
      {"infinity", [](Curves& c, Options&) { c.samples[27](9, 0) = -INFINITY; }, ErrorCode::NonFinite,
       "curve 27, sample 9: coordinate is not finite"},
      {"paper with 27 curves", [](Curves& c, Options& o) { c.samples.pop_back(), o.scheme = Scheme::Paper; },
       ErrorCode::InvalidArgument,
       "the paper scheme needs 3p+1 curves (4, 7, ..., 28: patches of 4 sharing their "
       "ends), got 27"},
      {"patch4 with 5 curves", [](Curves& c, Options& o) { c.samples.resize(5), o.scheme = Scheme::Patch4; },
       ErrorCode::InvalidArgument, "the patch4 scheme needs 3p+1 curves"},
      {"too many modes", [](Curves&, Options& o) { o.modes = 10; }, ErrorCode::InvalidArgument,
       "10 modes asked for, but curves of 10 samples hold at most 9"},
      {"zero a", [](Curves&, Options& o) { o.smoothing = 0.0; }, ErrorCode::InvalidArgument,
       "the smoothing parameter a must be positive and finite, got 0"},
      {"negative a", [](Curves&, Options& o) { o.smoothing = -1.0; }, ErrorCode::InvalidArgument,
       "the smoothing parameter a must be positive and finite, got -1"},
      {"nan a", [](Curves&, Options& o) { o.smoothing = NAN; }, ErrorCode::InvalidArgument,
       "the smoothing parameter a must be positive and finite, got nan"},
      {"infinite a", [](Curves&, Options& o) { o.smoothing = INFINITY; }, ErrorCode::InvalidArgument,
       "the smoothing parameter a must be positive and finite, got inf"},
      {"cap below 1", [](Curves&, Options& o) { o.patch4_max_amplification = 0.5; },
       ErrorCode::InvalidArgument, "the patch4 amplification cap must be at least 1, got 0.5"},
      {"curves out of order",
       [](Curves& c, Options& o) { std::swap(c.samples[4], c.samples[5]), o.spacing = Spacing::Physical; },
       ErrorCode::InvalidArgument,
       "physical spacing needs the curves in order of mean x: curve 5 (x = -47.5) does not follow curve 4 (x "
       "= -42.5)"},
      {"curves of no length",
       [](Curves& c, Options&) {
         for (Curve& k : c.samples)
           k.rowwise() = k.row(0).eval();
       },
       ErrorCode::InvalidArgument, "the curves have no length: give the smoothing parameter"},
      {"curves on top of each other",
       [](Curves& c, Options&) {
         for (Curve& k : c.samples)
           k = c.samples[0];
       },
       ErrorCode::InvalidArgument, "the curves have no width across them: give the smoothing parameter"},
  };
  for (const BadInput& bad : cases) {
    Curves curves = face::profiles(10);
    Options options;
    bad.change(curves, options);
    const auto s = Surface::build(curves, options, "face.pdef");
    ASSERT_FALSE(s.ok()) << bad.name;
    EXPECT_EQ(s.error().code, bad.code) << bad.name;
    EXPECT_EQ(s.error().message.substr(0, bad.message.size()), bad.message) << bad.name;
    EXPECT_EQ(s.error().source, "face.pdef") << bad.name;
  }
  // The same problems with a given a reach the curves' checks first; a given a skips the isotropic one.
  Curves flat = face::profiles(10);
  for (Curve& k : flat.samples)
    k.rowwise() = k.row(0).eval();
  EXPECT_TRUE(Surface::build(flat, {.smoothing = 1.0}).ok());
  EXPECT_FALSE(isotropic_smoothing(flat).ok());
}

TEST(PdeSurface, BadCallsThrow) {
  const Surface s = build(face::profiles(10), {});
  const std::vector<double> vs{0.0, 1.0};
  for (double u : {-1e-9, 9.0 + 1e-9, double(NAN), double(INFINITY)})
    EXPECT_THROW((void)s.evaluate(std::vector<double>{u}, vs), std::invalid_argument) << u;
  EXPECT_THROW((void)s.evaluate(std::vector<double>{1.0}, std::vector<double>{NAN}), std::invalid_argument);
  EXPECT_THROW((void)s.evaluate(1, 10), std::invalid_argument);
  EXPECT_THROW((void)s.mesh(10, 1), std::invalid_argument);
  EXPECT_THROW((void)triangulate(Grid{3, 3, std::vector<Vec3>(8)}), std::invalid_argument);
  EXPECT_THROW((void)triangulate(Grid{1, 3, std::vector<Vec3>(3)}), std::invalid_argument);
}

TEST(PdeSurface, EvaluationIsTheSameAtAnyResolutionAndDerivativesMatchDifferences) {
  const Surface s = build(face::profiles(30), {.modes = 12});
  const Grid coarse = s.evaluate(10, 7);
  const Grid fine = s.evaluate(19, 13); // every coarse point is on the fine grid
  for (std::size_t i = 0; i < 10; ++i)
    for (std::size_t k = 0; k < 7; ++k)
      EXPECT_LT((coarse(i, k) - fine(2 * i, 2 * k)).norm(), 1e-10);
  const Grid none = s.evaluate(std::vector<double>{}, std::vector<double>{1.1});
  EXPECT_EQ(none.u_count, 0u);
  EXPECT_TRUE(none.points.empty());
  const Grid single = s.evaluate(std::vector<double>{2.2}, std::vector<double>{1.1});
  const Grid block = s.evaluate(std::vector<double>{0.3, 2.2, 8.9}, std::vector<double>{0.0, 1.1});
  EXPECT_LT((single(0, 0) - block(1, 1)).norm(), 1e-10);
  // Outside [0, π] the surface is the even, 2π-periodic extension.
  const Grid mirrored =
      s.evaluate(std::vector<double>{2.2}, std::vector<double>{-1.1, 2 * std::numbers::pi - 1.1});
  EXPECT_LT((mirrored(0, 0) - single(0, 0)).norm(), 1e-10);
  EXPECT_LT((mirrored(0, 1) - single(0, 0)).norm(), 1e-10);
  const double h = 1e-6, u = 2.2, v = 1.1;
  const Grid du = s.evaluate(std::vector<double>{u}, std::vector<double>{v}, Derivative::U);
  const Grid dv = s.evaluate(std::vector<double>{u}, std::vector<double>{v}, Derivative::V);
  const Grid around = s.evaluate(std::vector<double>{u - h, u, u + h}, std::vector<double>{v - h, v, v + h});
  EXPECT_LT((du(0, 0) - (around(2, 1) - around(0, 1)) / (2 * h)).norm(), 1e-6 * du(0, 0).norm());
  EXPECT_LT((dv(0, 0) - (around(1, 2) - around(1, 0)) / (2 * h)).norm(), 1e-6 * dv(0, 0).norm());
}

TEST(PdeSurface, MeshIsARegularGridWithOutwardNormals) {
  const Surface s = build(face::profiles(30), {});
  const Mesh mesh = s.mesh(40, 30);
  EXPECT_EQ(mesh.vertex_count(), 1200u);
  EXPECT_EQ(mesh.triangle_count(), 2u * 39 * 29);
  EXPECT_EQ(mesh.units, Units::Millimetres);
  ASSERT_TRUE(validate(mesh).ok());
  ASSERT_TRUE(mesh.has_normals());
  for (const Vec3f& n : mesh.normals)
    EXPECT_GT(n.z(), 0.3f); // the face looks along +z
  // Vertex (i, k) is vertex k·u_count + i: the corners are the curves' ends.
  EXPECT_LT((mesh.positions[0] - Vec3(face::face_x(0), -90, face::ztrue(face::face_x(0), -90))).norm(), 1e-9);
  EXPECT_LT((mesh.positions[39] - Vec3(face::face_x(27), -90, face::ztrue(face::face_x(27), -90))).norm(),
            1e-9);
  EXPECT_LT((mesh.positions[29 * 40] - Vec3(face::face_x(0), 90, face::ztrue(face::face_x(0), 90))).norm(),
            1e-9);
}

TEST(PdeSurface, SchemeNames) {
  for (Scheme s : {Scheme::Spline, Scheme::Paper, Scheme::Patch4})
    EXPECT_EQ(value_named<Scheme>(kSchemeNames, to_string(s)), s);
  EXPECT_EQ(value_named<Scheme>(kSchemeNames, "Spline"), std::nullopt);
  EXPECT_EQ(value_named<Scheme>(kSchemeNames, ""), std::nullopt);
}

} // namespace

// Least-squares cubic splines: convergence at the cubic rate under the right parameterisation.

#include "pdeface/slice/spline.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <vector>

namespace pdeface::slice {
namespace {

// A smooth profile: y rises linearly with τ, z is a bump and a slope (mm).
Vec3 curve(double tau) { return {0.0, 100.0 * tau - 50.0, 20.0 * std::sin(3.0 * tau) + 10.0 * tau * tau}; }

// Samples clustered towards τ = 0 (as a scan's points cluster on steep parts), so that a parameter taken
// from the sample index would be wrong.
std::vector<Vec3> samples(std::size_t n) {
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < n; ++i)
    out.push_back(curve(std::pow(static_cast<double>(i) / static_cast<double>(n - 1), 1.5)));
  return out;
}

// The point at arc-length fraction t (a dense table of the arc length, interpolated).
class ArcTable {
public:
  ArcTable() {
    length_.push_back(0.0);
    for (int i = 1; i <= kSteps; ++i)
      length_.push_back(length_.back() + (curve(double(i) / kSteps) - curve(double(i - 1) / kSteps)).norm());
  }
  Vec3 at(double t) const {
    const double target = t * length_.back();
    const auto it = std::lower_bound(length_.begin(), length_.end(), target);
    const auto i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(1, it - length_.begin()));
    const double f = (target - length_[i - 1]) / (length_[i] - length_[i - 1]);
    return curve((static_cast<double>(i - 1) + f) / kSteps);
  }

private:
  static constexpr int kSteps = 200000;
  std::vector<double> length_;
};

// Largest distance between the spline at t and the curve's point for t, over a fine grid of t.
template <class Truth> double error(const Spline& s, const Truth& truth) {
  double worst = 0.0;
  for (int i = 0; i <= 2000; ++i) {
    const double t = i / 2000.0;
    worst = std::max(worst, (s.evaluate(t) - truth(t)).norm());
  }
  return worst;
}

template <class Truth>
std::vector<double> rates(Parameter parameter, std::size_t points, const Truth& truth) {
  const std::vector<Vec3> raw = samples(points);
  std::vector<double> e;
  for (std::size_t k : {8U, 16U, 32U, 64U}) {
    Result<Spline> s = fit_spline(raw, {.parameter = parameter, .controls = k});
    EXPECT_TRUE(s);
    e.push_back(error(*s, truth));
  }
  std::vector<double> out;
  for (std::size_t i = 1; i < e.size(); ++i)
    out.push_back(std::log2(e[i - 1] / e[i]));
  return out;
}

TEST(Spline, HeightParameterConvergesAtTheCubicRate) {
  // Equal t is equal height: the truth at t is the curve at y = lo + t (hi - lo), i.e. τ = t.
  for (double rate : rates(Parameter::Height, 300, [](double t) { return curve(t); }))
    EXPECT_GT(rate, 3.5);
}

TEST(Spline, ArcLengthParameterConvergesAtTheCubicRate) {
  const ArcTable table;
  // Dense samples so that chord length is arc length to well below the fit error.
  for (double rate : rates(Parameter::ArcLength, 3000, [&](double t) { return table.at(t); }))
    EXPECT_GT(rate, 3.5);
}

TEST(Spline, AWrongParameterDoesNotConverge) {
  // Against the arc-length truth, the height parameter stalls (this curve's speed is not constant):
  // the test above would fail for a fit that ignored the chosen parameterisation.
  const ArcTable table;
  const std::vector<Vec3> raw = samples(3000);
  Result<Spline> s = fit_spline(raw, {.parameter = Parameter::Height, .controls = 64});
  ASSERT_TRUE(s);
  EXPECT_GT(error(*s, [&](double t) { return table.at(t); }), 0.5);
}

TEST(Spline, ResampleIsUniformInTheParameterAndKeepsTheEnds) {
  const std::vector<Vec3> raw = samples(300);
  Result<Spline> s = fit_spline(raw, {.parameter = Parameter::Height, .controls = 30});
  ASSERT_TRUE(s);
  const std::vector<Vec3> k = s->resample(30);
  ASSERT_EQ(k.size(), 30U);
  for (std::size_t i = 0; i < k.size(); ++i)
    EXPECT_NEAR(k[i].y(), -50.0 + 100.0 * static_cast<double>(i) / 29.0, 1e-3);
  EXPECT_NEAR((k.front() - raw.front()).norm(), 0.0, 1e-3);
  EXPECT_NEAR((k.back() - raw.back()).norm(), 0.0, 1e-3);
  // A bridged hole or an occlusion jump leaves spans of the parameter without points: still defined.
  std::vector<Vec3> gap(raw.begin(), raw.begin() + 100);
  gap.insert(gap.end(), raw.begin() + 250, raw.end());
  Result<Spline> across = fit_spline(gap, {.parameter = Parameter::ArcLength, .controls = 40});
  ASSERT_TRUE(across);
  for (const Vec3& p : across->resample(200))
    EXPECT_LT(p.norm(), 80.0);
}

TEST(Spline, TheEndsAreThePointsEnds) {
  // A rough profile (a ±0.8 mm zigzag on the smooth curve, as a scan's section is near the jaw) fitted
  // with few control points: the least-squares ends used to land up to ~1 mm off the first and last
  // points, so the fitted curves missed the common height range they were clipped to.
  std::vector<Vec3> rough = samples(120);
  for (std::size_t i = 0; i < rough.size(); ++i)
    rough[i].z() += i % 2 == 0 ? 0.8 : -0.8;
  rough.back().z() += 3.0; // and a last point off the trend
  for (Parameter parameter : {Parameter::ArcLength, Parameter::Height})
    for (std::size_t k : {4U, 5U, 9U, 27U, 200U}) {
      Result<Spline> s = fit_spline(rough, {.parameter = parameter, .controls = k});
      ASSERT_TRUE(s) << k;
      const std::vector<Vec3> out = s->resample(k);
      EXPECT_EQ(out.front(), rough.front()) << k;
      EXPECT_NEAR((out.back() - rough.back()).norm(), 0.0, 1e-12) << k;
    }
}

TEST(Spline, BadFitsAreInvalidArguments) {
  const std::vector<Vec3> raw = samples(10);
  Result<Spline> three = fit_spline(raw, {.controls = 3});
  ASSERT_FALSE(three);
  EXPECT_EQ(three.error().code, ErrorCode::InvalidArgument);
  // More control points than points: the polyline between them is the data.
  Result<Spline> many = fit_spline(raw, {.controls = 40});
  ASSERT_TRUE(many);
  EXPECT_LT((many->evaluate(0.0) - raw.front()).norm(), 0.5);
  EXPECT_LT((many->evaluate(1.0) - raw.back()).norm(), 0.5);
  EXPECT_FALSE(fit_spline(std::vector<Vec3>{raw[0]}, {.controls = 4}));
  const std::vector<Vec3> flat(20, Vec3(1, 2, 3));
  Result<Spline> s = fit_spline(flat, {.controls = 4});
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().code, ErrorCode::InvalidArgument);
  EXPECT_THROW(Spline(std::vector<Vec3>(3)), std::invalid_argument);
}

} // namespace
} // namespace pdeface::slice

namespace pdeface::slice {
namespace {

// A profile of a face-like depth along its height, densely as a scan's section would be.
double depth(double y) { return 20.0 * std::exp(-y * y / 900.0) + 0.002 * y * y; }

// Samples at given heights sit at exactly those heights, on the profile (its depth there within the cosine
// fit's error), in its plane, ends held; heights that do not ascend, or not one per parameter, are refused.
TEST(CosineSamples, AtHeightsSitExactlyThereOnTheProfile) {
  std::vector<Vec3> profile;
  for (int i = 0; i <= 800; ++i) {
    const double y = -80.0 + 160.0 * i / 800.0;
    profile.emplace_back(3.0, y, depth(y));
  }
  // The polyline's arc length at each height: the parameters the heights stand at.
  std::vector<double> length{0.0};
  for (std::size_t i = 1; i < profile.size(); ++i)
    length.push_back(length.back() + (profile[i] - profile[i - 1]).norm());
  const std::size_t k = 24;
  std::vector<double> heights, at;
  for (std::size_t i = 0; i < k; ++i) {
    const double t =
        0.5 - 0.5 * std::cos(std::numbers::pi * static_cast<double>(i) / static_cast<double>(k - 1));
    heights.push_back(-80.0 + 160.0 * t);
    const auto n = static_cast<std::size_t>(std::lround(800.0 * t));
    at.push_back(length[n] / length.back());
  }
  at.front() = 0.0;
  at.back() = 1.0;
  const Result<std::vector<Vec3>> samples = cosine_samples(profile, at, heights);
  ASSERT_TRUE(samples) << samples.error().message;
  ASSERT_EQ(samples->size(), k);
  double worst = 0.0;
  for (std::size_t i = 0; i < k; ++i) {
    EXPECT_EQ((*samples)[i].y(), heights[i]) << i;
    EXPECT_NEAR((*samples)[i].x(), 3.0, 1e-9) << i;
    worst = std::max(worst, std::abs((*samples)[i].z() - depth(heights[i])));
  }
  EXPECT_EQ(samples->front(), profile.front());
  EXPECT_EQ(samples->back(), profile.back());
  EXPECT_LT(worst, 0.05) << "the samples' depth is the profile's at their heights";
  std::vector<double> descending = heights;
  std::swap(descending[3], descending[4]);
  EXPECT_EQ(cosine_samples(profile, at, descending).error().code, ErrorCode::InvalidArgument);
  EXPECT_EQ(cosine_samples(profile, at, std::span(heights).first(k - 1)).error().code,
            ErrorCode::InvalidArgument);
}

} // namespace
} // namespace pdeface::slice

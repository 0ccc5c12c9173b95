#include "pdeface/pde/surface.hpp"

#include "pdeface/pde/modes.hpp"

#include "basis.hpp"
#include "mode_solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace pdeface::pde {

std::string_view to_string(Scheme scheme) noexcept { return name_of<Scheme>(kSchemeNames, scheme); }

std::string_view to_string(Spacing spacing) noexcept { return name_of<Spacing>(kSpacingNames, spacing); }

namespace {

Error invalid(std::string message, std::string_view source) {
  return make_error(ErrorCode::InvalidArgument, std::move(message), std::string(source));
}

// Problems with the curves themselves, whatever the options.
std::optional<Error> check_curves(const Curves& curves, std::string_view source) {
  const auto& c = curves.samples;
  if (c.size() < 4) return invalid(fmt::format("need at least 4 curves, got {}", c.size()), source);
  for (std::size_t j = 0; j < c.size(); ++j) {
    if (c[j].rows() < 2)
      return invalid(fmt::format("curve {} has too few samples ({}): need at least 2", j, c[j].rows()),
                     source);
    if (c[j].rows() > static_cast<Eigen::Index>(max_samples))
      return invalid(
          fmt::format("curve {} has {} samples: at most {} are supported", j, c[j].rows(), max_samples),
          source);
    if (c[j].rows() != c[0].rows())
      return invalid(
          fmt::format("curve {} has {} samples but curve 0 has {}: every curve needs the same number", j,
                      c[j].rows(), c[0].rows()),
          source);
    for (Eigen::Index k = 0; k < c[j].rows(); ++k)
      if (!c[j].row(k).allFinite())
        return make_error(ErrorCode::NonFinite,
                          fmt::format("curve {}, sample {}: coordinate is not finite", j, k),
                          std::string(source));
  }
  return std::nullopt;
}

// Options that cannot work with these curves.
std::optional<Error> check_options(const Curves& curves, const Options& options, std::string_view source) {
  const std::size_t count = curves.samples.size();
  const auto samples = static_cast<std::size_t>(curves.samples[0].rows());
  if (options.scheme != Scheme::Spline && (count - 1) % 3 != 0)
    return invalid(fmt::format("the {} scheme needs 3p+1 curves (4, 7, ..., 28: patches of 4 sharing their "
                               "ends), got {}",
                               to_string(options.scheme), count),
                   source);
  if (options.modes && *options.modes > samples - 1)
    return invalid(fmt::format("{} modes asked for, but curves of {} samples hold at most {}", *options.modes,
                               samples, samples - 1),
                   source);
  if (options.smoothing && !(std::isfinite(*options.smoothing) && *options.smoothing > 0))
    return invalid(
        fmt::format("the smoothing parameter a must be positive and finite, got {:g}", *options.smoothing),
        source);
  if (!(options.patch4_max_amplification >= 1))
    return invalid(fmt::format("the patch4 amplification cap must be at least 1, got {:g}",
                               options.patch4_max_amplification),
                   source);
  return std::nullopt;
}

// The u range [0, (J−1)/3]: three curves per unit, as the paper's 28 curves over [0, 9].
double u_range(std::size_t curve_count) { return static_cast<double>(curve_count - 1) / 3.0; }

Result<double> isotropic(const Curves& curves, std::string_view source) {
  const auto& c = curves.samples;
  const Eigen::Index samples = c[0].rows();
  double length = 0, width = 0;
  for (const Curve& curve : c)
    length += (curve.bottomRows(samples - 1) - curve.topRows(samples - 1)).rowwise().norm().sum();
  for (std::size_t j = 0; j + 1 < c.size(); ++j)
    width += (c[j + 1] - c[j]).rowwise().norm().sum();
  length /= static_cast<double>(c.size());
  width /= static_cast<double>(samples) * u_range(c.size());
  if (!(length > 0) || !(width > 0))
    return invalid(fmt::format("the curves have no {}: give the smoothing parameter",
                               length > 0 ? "width across them" : "length"),
                   source);
  return std::numbers::pi * width / length;
}

// The smoothing parameter a: as given, else isotropic.
Result<double> smoothing_parameter(const Curves& curves, const Options& options, std::string_view source) {
  if (options.smoothing) return *options.smoothing;
  return isotropic(curves, source);
}

Result<std::vector<double>> curve_positions(const Curves& curves, Spacing spacing, std::string_view source) {
  const std::size_t count = curves.samples.size();
  std::vector<double> knots(count);
  if (spacing == Spacing::Uniform) {
    for (std::size_t j = 0; j < count; ++j)
      knots[j] = static_cast<double>(j) / 3.0;
    return knots;
  }
  std::vector<double> x(count);
  for (std::size_t j = 0; j < count; ++j)
    x[j] = curves.samples[j].col(0).mean();
  const double direction = x.back() > x.front() ? 1.0 : -1.0;
  for (std::size_t j = 1; j < count; ++j)
    if (!(direction * (x[j] - x[j - 1]) > 0))
      return invalid(
          fmt::format("physical spacing needs the curves in order of mean x: curve {} (x = {:g}) does "
                      "not follow curve {} (x = {:g})",
                      j, x[j], j - 1, x[j - 1]),
          source);
  const double scale = u_range(count) / (x.back() - x.front());
  for (std::size_t j = 0; j < count; ++j)
    knots[j] = (x[j] - x.front()) * scale;
  knots.back() = u_range(count);
  return knots;
}

bool within_cap(double amplification, const Options& options) {
  return std::isfinite(amplification) && amplification <= options.patch4_max_amplification;
}

// The highest frequency below `limit` that patch4 keeps within the cap; −1 when not even frequency 0 does.
double highest_stable_frequency(double limit, double a, const Options& options,
                                const std::vector<double>& knots,
                                const std::vector<detail::PieceSpan>& pieces) {
  double stable = -1;
  for (double f = 0; f < limit; ++f) {
    if (!within_cap(detail::ModeSolver(Scheme::Patch4, knots, pieces, a, f).amplification(), options)) break;
    stable = f;
  }
  return stable;
}

// Patch4 beyond its cap: say which frequencies would be stable.
Error patch4_refusal(double worst, double top_frequency, double a, const Options& options,
                     const std::vector<double>& knots, const std::vector<detail::PieceSpan>& pieces,
                     std::string_view source) {
  const double stable = highest_stable_frequency(top_frequency, a, options, knots, pieces);
  const std::string advice =
      stable < 0 ? std::string("no frequency stays within the cap: use the spline scheme")
                 : fmt::format(
                       "its highest stable frequency is {0:g}, so use at most {1:g} modes with the remainder "
                       "(which takes frequency N+1) or {0:g} without, a smaller smoothing parameter, or the "
                       "spline scheme",
                       stable, std::max(0.0, stable - 1));
  return invalid(
      fmt::format("patch4 would amplify the curves' data {:.3g}-fold at frequency {:g} (a = {:g}, cap "
                  "{:g}): {}",
                  worst, top_frequency, a, options.patch4_max_amplification, advice),
      source);
}

} // namespace

Result<double> isotropic_smoothing(const Curves& curves) {
  if (auto error = check_curves(curves, {})) return *error;
  return isotropic(curves, {});
}

Result<std::size_t> max_modes(const Curves& curves, const Options& options, std::string_view source) {
  if (auto error = check_curves(curves, source)) return *error;
  Options all = options;
  all.modes.reset();
  if (auto error = check_options(curves, all, source)) return *error;
  const auto top = static_cast<std::size_t>(curves.samples[0].rows()) - 1;
  if (options.scheme != Scheme::Patch4) return top;

  const Result<double> a = smoothing_parameter(curves, options, source);
  if (!a) return a.error();
  auto knots = curve_positions(curves, options.spacing, source);
  if (!knots) return std::move(knots).error();
  const double stable = highest_stable_frequency(static_cast<double>(top) + 1, *a, options, *knots,
                                                 detail::piece_spans(Scheme::Patch4, *knots));
  if (stable >= static_cast<double>(top)) return top; // every mode fits: no remainder needed
  // The remainder takes frequency N+1, so with it one mode fewer fits.
  const double modes = options.remainder ? stable - 1 : stable;
  if (modes < 0)
    return invalid(
        fmt::format("patch4 amplifies even the lowest modes more than {:g}-fold (a = {:g}): use the "
                    "spline scheme",
                    options.patch4_max_amplification, *a),
        source);
  return static_cast<std::size_t>(modes);
}

Result<Surface> Surface::build(const Curves& curves, const Options& options, std::string_view source) {
  if (auto error = check_curves(curves, source)) return *error;
  if (auto error = check_options(curves, options, source)) return *error;
  const std::size_t count = curves.samples.size();
  const auto samples = static_cast<std::size_t>(curves.samples[0].rows());

  Surface s;
  s.scheme_ = options.scheme;
  s.units_ = curves.units;
  s.sample_count_ = samples;
  s.modes_ = options.modes.value_or(samples - 1);
  s.columns_ = options.remainder ? samples : s.modes_ + 1;
  const Result<double> a = smoothing_parameter(curves, options, source);
  if (!a) return a.error();
  s.a_ = *a;
  auto knots = curve_positions(curves, options.spacing, source);
  if (!knots) return std::move(knots).error();
  s.knots_ = std::move(knots).value();
  const std::vector<detail::PieceSpan> spans = detail::piece_spans(s.scheme_, s.knots_);

  if (s.scheme_ == Scheme::Patch4) { // amplification grows with m: the highest frequency decides
    const double top = s.frequency(s.columns_ - 1);
    const double worst = detail::ModeSolver(s.scheme_, s.knots_, spans, s.a_, top).amplification();
    if (!within_cap(worst, options))
      return patch4_refusal(worst, top, s.a_, options, s.knots_, spans, source);
  }

  // Every coordinate of every curve in cosines: column 3j + c holds coordinate c of curve j.
  Eigen::MatrixXd stacked(static_cast<Eigen::Index>(samples), static_cast<Eigen::Index>(3 * count));
  for (std::size_t j = 0; j < count; ++j)
    stacked.middleCols<3>(static_cast<Eigen::Index>(3 * j)) = curves.samples[j];
  const Eigen::MatrixXd alpha = cosine_coefficients(stacked);

  // Solve every column: its own frequency for n ≤ N, frequency N+1 for all the remainder's columns.
  for (const auto& span : spans)
    s.pieces_.push_back(
        {span.start, span.length,
         Eigen::Matrix<double, 3, Eigen::Dynamic>(3, static_cast<Eigen::Index>(4 * s.columns_))});
  std::optional<detail::ModeSolver> solver;
  std::vector<detail::PieceCoefficients> solved;
  detail::ModeValues values(static_cast<Eigen::Index>(count), 3);
  for (std::size_t n = 0; n < s.columns_; ++n) {
    if (n == 0 || s.frequency(n) != s.frequency(n - 1))
      solver.emplace(s.scheme_, s.knots_, spans, s.a_, s.frequency(n));
    for (std::size_t j = 0; j < count; ++j)
      values.row(static_cast<Eigen::Index>(j)) =
          alpha.block<1, 3>(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(3 * j));
    solver->solve(values, solved);
    for (std::size_t p = 0; p < spans.size(); ++p)
      s.pieces_[p].coefficients.middleCols<4>(static_cast<Eigen::Index>(4 * n)) = solved[p].transpose();
  }
  return s;
}

} // namespace pdeface::pde

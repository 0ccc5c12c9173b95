#include "pdeface/pipeline/table.hpp"

#include "pdeface/core/parallel.hpp"
#include "pdeface/pipeline/reconstruct.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pdeface::pipeline {
namespace {

TableRow measure_row(const Mesh& canonical, const slice::ProfileSet& profiles, double ratio,
                     pde::Scheme scheme, const TableOptions& options, std::string_view source) {
  TableRow row{.scan = std::string(source), .ratio = ratio, .k = profiles.k, .scheme = scheme};
  pde::Options pde = options.pde;
  pde.scheme = scheme;
  const pde::Curves curves = to_curves(profiles);
  if (scheme == pde::Scheme::Patch4) {
    Result<std::size_t> most = pde::max_modes(curves, pde, source);
    if (!most) {
      row.failure = most.error().message;
      return row;
    }
    pde.modes = std::min(*most, pde.modes.value_or(*most));
  }
  Result<pde::Surface> surface = pde::Surface::build(curves, pde, source);
  if (!surface) {
    row.failure = surface.error().message;
    return row;
  }
  row.modes = surface->modes();
  row.smoothing = surface->smoothing();
  const Resolution grid = resolution_for(profiles, options.grid_spacing_mm);
  Result<metrics::Fidelity> fidelity =
      metrics::measure_fidelity(canonical, profiles, surface->mesh(grid.u, grid.v), options.fidelity);
  if (!fidelity)
    row.failure = fidelity.error().message;
  else
    row.fidelity = *fidelity;
  return row;
}

// Mean of `value` over the rows of one ratio and scheme that have a fidelity; NaN when none.
template <class Value>
double mean_over_scans(std::span<const TableRow> rows, double ratio, pde::Scheme scheme, Value value) {
  double sum = 0.0;
  int count = 0;
  for (const TableRow& r : rows)
    if (r.ratio == ratio && r.scheme == scheme && r.fidelity) {
      sum += value(*r.fidelity);
      ++count;
    }
  return count ? sum / count : std::numeric_limits<double>::quiet_NaN();
}

} // namespace

Result<std::vector<TableRow>> table_rows(const Mesh& scan, const align::Alignment& alignment,
                                         const TableOptions& options, std::string_view source) {
  const CanonicalScan canonical = canonical_scan(scan, alignment);
  std::vector<slice::ProfileSet> sets; // one per ratio
  for (double ratio : options.ratios) {
    slice::ProfileOptions profile_options = options.profiles;
    profile_options.ratio = ratio;
    profile_options.points.reset();
    Result<slice::ProfileSet> profiles = extract_profiles(canonical, profile_options);
    if (!profiles) return with_source(std::move(profiles).error(), source);
    sets.push_back(std::move(profiles).value());
  }
  // Every row is independent (solving, meshing and measuring are pure): spread them over the cores.
  std::vector<TableRow> rows(sets.size() * options.schemes.size());
  parallel_for(rows.size(), 0, [&](std::size_t i) {
    const std::size_t r = i / options.schemes.size(), s = i % options.schemes.size();
    rows[i] = measure_row(canonical.mesh, sets[r], options.ratios[r], options.schemes[s], options, source);
  });
  return rows;
}

namespace {

std::string number(double value) {
  return std::isnan(value) ? std::string("–") : fmt::format("{:.3f}", value);
}
std::string csv_number(double value) {
  return std::isnan(value) ? std::string() : fmt::format("{:.6g}", value);
}
std::string percent(double ratio) { return fmt::format("{:g} %", 100.0 * ratio); }

// The distinct ratios and schemes of the rows, in first-seen order.
template <class T, class Get> std::vector<T> distinct(std::span<const TableRow> rows, Get get) {
  std::vector<T> out;
  for (const TableRow& r : rows)
    if (std::find(out.begin(), out.end(), get(r)) == out.end()) out.push_back(get(r));
  return out;
}

// "14" or "14–16": the points per curve of one ratio across the scans.
std::string k_range(std::span<const TableRow> rows, double ratio) {
  std::size_t lo = std::numeric_limits<std::size_t>::max(), hi = 0;
  for (const TableRow& r : rows)
    if (r.ratio == ratio) {
      lo = std::min(lo, r.k);
      hi = std::max(hi, r.k);
    }
  return lo == hi ? fmt::format("{}", lo) : fmt::format("{}–{}", lo, hi);
}

template <class Value>
void summary(std::string& out, std::span<const TableRow> rows, std::string_view title, Value value) {
  const auto ratios = distinct<double>(rows, [](const TableRow& r) { return r.ratio; });
  const auto schemes = distinct<pde::Scheme>(rows, [](const TableRow& r) { return r.scheme; });
  out += fmt::format("\n## {}\n\n| ratio | K |", title);
  for (pde::Scheme s : schemes)
    out += fmt::format(" {} |", pde::to_string(s));
  out += "\n|---:|---:|";
  for (std::size_t i = 0; i < schemes.size(); ++i)
    out += "---:|";
  out += "\n";
  for (double ratio : ratios) {
    out += fmt::format("| {} | {} |", percent(ratio), k_range(rows, ratio));
    for (pde::Scheme s : schemes)
      out += fmt::format(" {} |", number(mean_over_scans(rows, ratio, s, value)));
    out += "\n";
  }
}

} // namespace

std::string table_markdown(std::span<const TableRow> rows) {
  const auto scans = distinct<std::string>(rows, [](const TableRow& r) { return r.scan; });
  std::string out = "# Profile error and surface distance by sampling ratio\n\n";
  out += fmt::format("Scans ({}): {}. Units: mm. Figures are means over the scans.\n", scans.size(),
                     fmt::join(scans, ", "));
  out +=
      "Profile error: the paper's Table I measure, the mean distance from the reconstructed to the original "
      "profile on 4 planes (symmetry, eyes, two diagonals through the nose tip), averaged over the planes. "
      "Surface distance: two-sided, between the scan and the PDE surface within the face region the "
      "curves cover (the reconstruction's side leaves out the holes it filled). Face coverage: how much of "
      "the face, as its landmarks outline it (an ellipse from the chin to the forehead, across the cheeks "
      "just beyond the outer eye corners), lies within 1 mm of the reconstruction, whatever the region the "
      "curves cover.\n";
  summary(out, rows, "Profile error (mm)", [](const metrics::Fidelity& f) { return f.mean_profile_error; });
  summary(out, rows, "Profile error on the curves' own planes (mm)",
          [](const metrics::Fidelity& f) { return f.curve_error; });
  summary(out, rows, "Surface distance, mean (mm)",
          [](const metrics::Fidelity& f) { return f.surface.both.mean; });
  summary(out, rows, "Surface distance, 95th percentile (mm)",
          [](const metrics::Fidelity& f) { return f.surface.both.p95; });
  summary(out, rows, "Face coverage: share of the scan's face mask within 1 mm of the reconstruction (%)",
          [](const metrics::Fidelity& f) { return 100.0 * f.coverage.share; });
  summary(out, rows, "Face mask: scan to reconstruction, mean (mm)",
          [](const metrics::Fidelity& f) { return f.coverage.distance.mean; });

  out +=
      "\n## Every scan\n\n| scan | ratio | K | scheme | N | a | symmetry | eyes | diagonal up | diagonal "
      "down | profile error | on the curves | surface mean | RMS | p95 | max | max / diagonal | coverage | "
      "mask mean |\n"
      "|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const TableRow& r : rows) {
    out += fmt::format("| {} | {} | {} | {} |", r.scan, percent(r.ratio), r.k, pde::to_string(r.scheme));
    if (!r.fidelity) {
      out += fmt::format(" – | – | failed: {} |{}\n", r.failure,
                         std::string_view(" |  |  |  |  |  |  |  |  |  |  |  |"));
      continue;
    }
    const metrics::Fidelity& f = *r.fidelity;
    const metrics::DistanceStats& d = f.surface.both;
    out += fmt::format(
        " {} | {:.3f} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {:.2e} | {:.1f} % | {} |\n",
        r.modes, r.smoothing, number(f.profile_error[0]), number(f.profile_error[1]),
        number(f.profile_error[2]), number(f.profile_error[3]), number(f.mean_profile_error),
        number(f.curve_error), number(d.mean), number(d.rms), number(d.p95), number(d.max),
        d.max / f.surface.diagonal, 100.0 * f.coverage.share, number(f.coverage.distance.mean));
  }
  return out;
}

std::string table_csv(std::span<const TableRow> rows) {
  std::string out =
      "scan,ratio,k,scheme,modes,smoothing,profile_symmetry_mm,profile_eyes_mm,"
      "profile_diagonal_up_mm,profile_diagonal_down_mm,profile_mean_mm,curve_error_mm,surface_mean_mm,"
      "surface_rms_mm,surface_p95_mm,surface_max_mm,diagonal_mm,coverage,mask_mean_mm,failure\n";
  const auto quoted = [](const std::string& text) {
    std::string q = "\"";
    for (char c : text)
      q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
  };
  for (const TableRow& r : rows) {
    out += fmt::format("{},{:g},{},{},", quoted(r.scan), r.ratio, r.k, pde::to_string(r.scheme));
    if (r.fidelity) {
      const metrics::Fidelity& f = *r.fidelity;
      const metrics::DistanceStats& d = f.surface.both;
      out += fmt::format(
          "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},", r.modes, csv_number(r.smoothing),
          csv_number(f.profile_error[0]), csv_number(f.profile_error[1]), csv_number(f.profile_error[2]),
          csv_number(f.profile_error[3]), csv_number(f.mean_profile_error), csv_number(f.curve_error),
          csv_number(d.mean), csv_number(d.rms), csv_number(d.p95), csv_number(d.max),
          csv_number(f.surface.diagonal), csv_number(f.coverage.share), csv_number(f.coverage.distance.mean));
    } else {
      out += std::string(15, ',') + quoted(r.failure);
    }
    out += "\n";
  }
  return out;
}

} // namespace pdeface::pipeline

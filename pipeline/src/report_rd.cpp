// Rate and distortion of the `.pdef` with a residual layer against decimate + Draco at the same byte
// budgets: per scan, and across scans (median and worst scan of the mean, p95 and max mesh → scan).

#include "report_detail.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace pdeface::pipeline::detail {
namespace {

struct Point {
  double bytes = 0, mean = 0, p95 = 0, max = 0;
};

// The residual rows and decimate + Draco rows of one scan, by budget.
std::map<std::size_t, std::pair<std::optional<Point>, std::optional<Point>>>
by_budget(const ScanReport& scan) {
  std::map<std::size_t, std::pair<std::optional<Point>, std::optional<Point>>> out;
  for (const Variant& v : scan.variants) {
    if (!v.fidelity || v.budget == 0) continue;
    const Point p{static_cast<double>(v.bytes), v.fidelity->to_scan.mean, v.fidelity->to_scan.p95,
                  v.fidelity->to_scan.max};
    if (v.method == Method::Pde)
      out[v.budget].first = p;
    else if (v.method == Method::DecimateDraco && v.name == fmt::format("decimate+draco {} B", v.budget))
      out[v.budget].second = p;
  }
  return out;
}

std::string triple(const Point& p) { return fmt::format("{:.3f} / {:.3f} / {:.3f}", p.mean, p.p95, p.max); }

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

} // namespace

Table rd_scan_table(const ScanReport& scan) {
  Table t{.header = {"budget", ".pdef bytes", ".pdef mean / p95 / max", "decimate+draco bytes",
                     "decimate+draco mean / p95 / max", ".pdef better (mean, p95)", "max ratio"},
          .right = {true, true, true, true, true, false, true}};
  for (const auto& [budget, pair] : by_budget(scan)) {
    const auto& [pdef, mesh] = pair;
    if (!pdef) continue;
    t.rows.push_back({fmt::format("{}", budget), fmt::format("{:.0f}", pdef->bytes), triple(*pdef),
                      mesh ? fmt::format("{:.0f}", mesh->bytes) : "–", mesh ? triple(*mesh) : "–",
                      mesh ? fmt::format("{}, {}", pdef->mean < mesh->mean ? "yes" : "no",
                                         pdef->p95 < mesh->p95 ? "yes" : "no")
                           : "–",
                      mesh ? fmt::format("{:.2f}", pdef->max / mesh->max) : "–"});
  }
  return t;
}

Table rd_summary_table(const Report& report) {
  struct Column {
    std::vector<double> mean, p95, max, bytes;
    double worst_mean = 0, worst_p95 = 0, worst_max = 0;
  };
  std::map<std::size_t, std::pair<Column, Column>> columns;
  std::map<std::size_t, std::size_t> wins, scans, max_within;
  for (const ScanReport& scan : report.scans)
    for (const auto& [budget, pair] : by_budget(scan)) {
      const auto& [pdef, mesh] = pair;
      if (!pdef) continue;
      auto add = [](Column& c, const Point& p) {
        c.mean.push_back(p.mean);
        c.p95.push_back(p.p95);
        c.max.push_back(p.max);
        c.bytes.push_back(p.bytes);
        c.worst_mean = std::max(c.worst_mean, p.mean);
        c.worst_p95 = std::max(c.worst_p95, p.p95);
        c.worst_max = std::max(c.worst_max, p.max);
      };
      add(columns[budget].first, *pdef);
      if (!mesh) continue;
      add(columns[budget].second, *mesh);
      ++scans[budget];
      if (pdef->mean < mesh->mean && pdef->p95 < mesh->p95) ++wins[budget];
      if (pdef->max <= 1.5 * mesh->max) ++max_within[budget];
    }
  Table t{.header = {"budget", ".pdef bytes (median)", ".pdef mean / p95 / max: median scan",
                     ".pdef worst scan", "decimate+draco mean / p95 / max: median scan",
                     "decimate+draco worst scan", ".pdef mean and p95 below", ".pdef max within 1.5×"},
          .right = {true, true, true, true, true, true, true, true}};
  for (const auto& [budget, pair] : columns) {
    const auto& [p, m] = pair;
    auto med = [](const Column& c) {
      return Point{median(c.bytes), median(c.mean), median(c.p95), median(c.max)};
    };
    auto worst = [](const Column& c) { return Point{0, c.worst_mean, c.worst_p95, c.worst_max}; };
    t.rows.push_back({fmt::format("{}", budget), fmt::format("{:.0f}", median(p.bytes)), triple(med(p)),
                      triple(worst(p)), m.mean.empty() ? "–" : triple(med(m)),
                      m.mean.empty() ? "–" : triple(worst(m)),
                      fmt::format("{} of {}", wins[budget], scans[budget]),
                      fmt::format("{} of {}", max_within[budget], scans[budget])});
  }
  return t;
}

} // namespace pdeface::pipeline::detail

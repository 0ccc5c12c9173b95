// The report as pictures: the size-against-error plot, the page with everything on it, and the set of
// files a report folder holds.

#include "heat_map.hpp"
#include "report_detail.hpp"

#include "pdeface/core/file.hpp"
#include "pdeface/svg/svg.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace pdeface::pipeline {
namespace detail {

std::string html(const Table& table) {
  std::string out = "<table>\n<tr>";
  for (const std::string& h : table.header)
    out += "<th>" + svg::escape(h) + "</th>";
  out += "</tr>\n";
  for (const auto& row : table.rows) {
    out += "<tr>";
    for (std::size_t c = 0; c < row.size(); ++c)
      out += fmt::format("<td{}>{}</td>", c < table.right.size() && table.right[c] ? " class=\"r\"" : "",
                         svg::escape(row[c]));
    out += "</tr>\n";
  }
  return out + "</table>\n";
}

} // namespace detail

namespace {

struct Series {
  std::string label;
  std::string colour;
  bool line = true;
  std::vector<std::pair<double, double>> points; // bytes, error
  std::vector<std::string> tags;                 // a short label per point
};

std::string tag_of(const detail::Aggregate& a) {
  if (a.method == Method::Draco) return a.name.substr(6, a.name.find(' ', 6) - 6); // "draco 11 bits" -> 11
  if (a.method == Method::Pde) return a.name.substr(4, a.name.find('%') - 3);      // "pde 10 % ..." -> 10 %
  return {}; // raw files: the legend says which; decimate + Draco: its budgets follow the x axis
}

std::vector<Series> series_of(const Report& report) {
  std::vector<Series> out{{"raw (OBJ, PLY, VRML, GLB)", "#7f7f7f", false, {}, {}},
                          {"raw + gzip", "#bcbd22", false, {}, {}},
                          {"Draco (bits)", "#1f77b4", true, {}, {}},
                          {"decimate + Draco", "#ff7f0e", true, {}, {}},
                          {"PDE .pdef lossy (ratio)", "#2ca02c", true, {}, {}},
                          {"PDE .pdef lossless (ratio)", "#9467bd", true, {}, {}}};
  for (const detail::Aggregate& a : detail::aggregate(report)) {
    if (a.bytes.n == 0 || !std::isfinite(a.mask_mean.mean)) continue;
    std::size_t s = 0;
    switch (a.method) {
    case Method::Raw: s = 0; break;
    case Method::Gzip: s = 1; break;
    case Method::Draco: s = 2; break;
    case Method::DecimateDraco: s = 3; break;
    case Method::Pde: s = a.name.find("lossless") != std::string::npos ? 5 : 4; break;
    case Method::DracoColour:
    case Method::PdeTexture: continue; // their geometry is another row's: measured on colour (report.md)
    }
    out[s].points.emplace_back(a.bytes.mean, a.mask_mean.mean);
    out[s].tags.push_back(tag_of(a));
  }
  for (Series& s : out) { // along the x axis
    std::vector<std::size_t> order(s.points.size());
    for (std::size_t i = 0; i < order.size(); ++i)
      order[i] = i;
    std::ranges::sort(order, {}, [&](std::size_t i) { return s.points[i].first; });
    Series sorted{s.label, s.colour, s.line, {}, {}};
    for (std::size_t i : order) {
      sorted.points.push_back(s.points[i]);
      sorted.tags.push_back(s.tags[i]);
    }
    s = std::move(sorted);
  }
  std::erase_if(out, [](const Series& s) { return s.points.empty(); });
  return out;
}

// 1, 2, 5 × 10^k at or above `v`.
double nice_ceiling(double v) {
  if (!(v > 0)) return 1.0;
  const double p = std::pow(10.0, std::floor(std::log10(v)));
  for (double m : {1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0})
    if (m * p >= v) return m * p;
  return 10.0 * p;
}

std::string bytes_label(double b) { // SI, as the decades fall
  if (b >= 1e6) return fmt::format("{:g} MB", b / 1e6);
  if (b >= 1e3) return fmt::format("{:g} kB", b / 1e3);
  return fmt::format("{:g} B", b);
}

std::string inline_markdown(std::string_view text) { // **bold** and "- " items, escaped
  std::string out, line;
  bool list = false;
  const auto flush = [&] {
    std::string html;
    bool bold = false;
    const std::string escaped = svg::escape(line);
    for (std::size_t i = 0; i < escaped.size(); ++i) {
      if (escaped.compare(i, 2, "**") == 0) {
        html += bold ? "</b>" : "<b>";
        bold = !bold;
        ++i;
      } else {
        html += escaped[i];
      }
    }
    const bool item = line.starts_with("- ");
    if (item && !list) out += "<ul>\n";
    if (!item && list) out += "</ul>\n";
    list = item;
    out += item ? "<li>" + html.substr(2) + "</li>\n" : "<p>" + html + "</p>\n";
    line.clear();
  };
  for (char c : text) {
    if (c == '\n')
      flush();
    else
      line += c;
  }
  if (!line.empty()) flush();
  if (list) out += "</ul>\n";
  return out;
}

std::string colour_bar(double scale_mm) {
  std::string stops;
  for (int i = 0; i <= 8; ++i) {
    const Eigen::Vector3f c = detail::heat_colour(scale_mm * i / 8.0, scale_mm);
    stops += fmt::format("<stop offset=\"{:g}\" stop-color=\"rgb({:.0f},{:.0f},{:.0f})\"/>", i / 8.0,
                         255 * c[0], 255 * c[1], 255 * c[2]);
  }
  return fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"360\" height=\"34\" font-family=\"sans-serif\" "
      "font-size=\"11\"><defs><linearGradient id=\"heat\">{}</linearGradient></defs>"
      "<rect x=\"10\" y=\"2\" width=\"260\" height=\"14\" fill=\"url(#heat)\"/>"
      "<text x=\"10\" y=\"30\">0 mm</text><text x=\"270\" y=\"30\" text-anchor=\"end\">{:g} mm and "
      "beyond</text>"
      "<rect x=\"290\" y=\"2\" width=\"14\" height=\"14\" fill=\"rgb(199,199,199)\"/>"
      "<text x=\"308\" y=\"13\">not judged</text></svg>",
      stops, scale_mm);
}

} // namespace

std::string rd_svg(const Report& report) {
  const std::vector<Series> series = series_of(report);
  constexpr double kWidth = 860, kHeight = 500, kLeft = 70, kRight = 230, kTop = 40, kBottom = 60;
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0, top = 0.0;
  for (const Series& s : series)
    for (const auto& [b, e] : s.points) {
      lo = std::min(lo, b);
      hi = std::max(hi, b);
      top = std::max(top, e);
    }
  if (series.empty()) lo = 100, hi = 1e6, top = 1.0;
  const double x0 = std::floor(std::log10(lo)), x1 = std::max(x0 + 1.0, std::ceil(std::log10(hi)));
  const double y1 = nice_ceiling(top * 1.05);
  const double pw = kWidth - kLeft - kRight, ph = kHeight - kTop - kBottom;
  const auto px = [&](double b) { return kLeft + pw * (std::log10(b) - x0) / (x1 - x0); };
  const auto py = [&](double e) { return kTop + ph * (1.0 - e / y1); };
  std::string doc = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {0} {1}\" width=\"{0}\" height=\"{1}\" "
      "font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"{0}\" height=\"{1}\" fill=\"white\"/>\n"
      "<text x=\"{2}\" y=\"22\" font-size=\"15\">Size against error{3}</text>\n",
      kWidth, kHeight, kLeft,
      report.scans.size() > 1 ? fmt::format(" (mean over {} scans)", report.scans.size() - report.failed())
                              : std::string());
  // Grid and axes: decades (and 2, 5 between) across, five steps up.
  for (double d = x0; d <= x1 + 1e-9; d += 1.0)
    for (double m : {1.0, 2.0, 5.0}) {
      const double b = m * std::pow(10.0, d);
      if (std::log10(b) > x1 + 1e-9) continue;
      doc += fmt::format("<line x1=\"{0:.1f}\" x2=\"{0:.1f}\" y1=\"{1}\" y2=\"{2}\" stroke=\"{3}\"/>\n",
                         px(b), kTop, kTop + ph, m == 1.0 ? "#bbb" : "#eee");
      if (m == 1.0)
        doc += fmt::format("<text x=\"{:.1f}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n", px(b),
                           kTop + ph + 16, bytes_label(b));
    }
  for (int k = 0; k <= 5; ++k) {
    const double e = y1 * k / 5.0;
    doc += fmt::format("<line x1=\"{0}\" x2=\"{1}\" y1=\"{2:.1f}\" y2=\"{2:.1f}\" stroke=\"#ddd\"/>\n"
                       "<text x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">{5:g}</text>\n",
                       kLeft, kLeft + pw, py(e), kLeft - 6, py(e) + 4, e);
  }
  doc += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#333\"/>\n",
                     kLeft, kTop, pw, ph);
  doc += fmt::format("<text x=\"{:.1f}\" y=\"{}\" text-anchor=\"middle\">bytes (log scale)</text>\n",
                     kLeft + pw / 2, kHeight - 18);
  doc += fmt::format(
      "<text transform=\"translate(18,{:.1f}) rotate(-90)\" text-anchor=\"middle\">mean distance, "
      "scan's face → decoded mesh (mm)</text>\n",
      kTop + ph / 2);
  // The series, and the legend beside the plot.
  for (std::size_t i = 0; i < series.size(); ++i) {
    const Series& s = series[i];
    if (s.line && s.points.size() > 1) {
      std::string points;
      for (const auto& [b, e] : s.points)
        points += fmt::format("{:.1f},{:.1f} ", px(b), py(e));
      doc += fmt::format("<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"2\" points=\"{}\"/>\n",
                         s.colour, points);
    }
    // A point's tag unless it would overlap the series' last tag drawn (about 6 px a character, 10 px high).
    double tag_x = -1e9, tag_y = -1e9, tag_width = 0;
    for (std::size_t k = 0; k < s.points.size(); ++k) {
      const auto [b, e] = s.points[k];
      doc +=
          fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"4\" fill=\"{}\"/>\n", px(b), py(e), s.colour);
      const double x = px(b) + 5, y = py(e) - 5;
      const bool crowded = std::abs(x - tag_x) < tag_width + 4 && std::abs(y - tag_y) < 11;
      if (s.tags[k].empty() || crowded) continue;
      doc += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"10\" fill=\"{}\">{}</text>\n", x, y,
                         s.colour, svg::escape(s.tags[k]));
      tag_x = x;
      tag_y = y;
      tag_width = 6.0 * static_cast<double>(s.tags[k].size());
    }
    const double ly = kTop + 10 + 22.0 * static_cast<double>(i), lx = kLeft + pw + 16;
    doc += fmt::format(
        "<line x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\" stroke=\"{3}\" stroke-width=\"{4}\"/>"
        "<circle cx=\"{5}\" cy=\"{2}\" r=\"4\" fill=\"{3}\"/>"
        "<text x=\"{6}\" y=\"{7}\">{8}</text>\n",
        lx, lx + 24, ly, s.colour, s.line ? 2 : 0, lx + 12, lx + 30, ly + 4, svg::escape(s.label));
  }
  return doc + "</svg>\n";
}

std::string report_html(const Report& report) {
  std::string page =
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>pdeface compare</title>\n"
      "<style>body{font-family:sans-serif;margin:2em;max-width:1500px;color:#222}"
      "table{border-collapse:collapse;font-size:12px;margin:0.5em 0 1.5em}"
      "th,td{border:1px solid #ccc;padding:2px 6px}th{background:#f3f3f3}td.r{text-align:right}"
      "figure{display:inline-block;margin:0 1em 1em 0;vertical-align:top}"
      "figcaption{font-size:12px;text-align:center}</style></head><body>\n";
  page += "<h1>pdeface compare: size and fidelity</h1>\n";
  page += fmt::format("<p>{} scan{} ({} failed), {:.1f} s.</p>\n", report.scans.size(),
                      report.scans.size() == 1 ? "" : "s", report.failed(), report.seconds);
  page += inline_markdown(detail::method_notes(report));
  page += "<h2>Summary across scans (mean ± sd)</h2>\n" + detail::html(detail::summary_table(report));
  page += "<h2>Size against error</h2>\n" + rd_svg(report);
  bool any_heat = false;
  for (const ScanReport& scan : report.scans)
    any_heat = any_heat || !scan.heat_maps.empty();
  if (any_heat) {
    page += "<h2>Heat maps: each point's distance to the scan</h2>\n" +
            colour_bar(report.options.heat_max_mm) + "<br>\n";
    for (const ScanReport& scan : report.scans)
      for (const HeatMap& h : scan.heat_maps)
        page += fmt::format("<figure>{}<figcaption>{}: {} (<a href=\"{}\">{}</a>)</figcaption></figure>\n",
                            h.front_svg, svg::escape(scan.name), svg::escape(h.variant), svg::escape(h.file),
                            svg::escape(h.file));
  }
  for (const ScanReport& scan : report.scans) {
    page += "<h2>" + svg::escape(detail::scan_heading(scan)) + "</h2>\n";
    if (!scan.failure.empty()) {
      page += "<p>" + svg::escape(scan.failure) + "</p>\n";
      continue;
    }
    page += fmt::format("<p>Raw binary PLY: {} bytes.</p>\n", scan.ply_bytes) +
            detail::html(detail::scan_table(scan));
  }
  return page + "</body></html>\n";
}

std::vector<OutputFile> report_files(const Report& report, const std::filesystem::path& folder) {
  std::vector<OutputFile> files{{folder / "report.md", report_markdown(report)},
                                {folder / "report.json", report_json(report)},
                                {folder / "report.csv", report_csv(report)},
                                {folder / "rd.svg", rd_svg(report)},
                                {folder / "report.html", report_html(report)}};
  for (const ScanReport& scan : report.scans) {
    for (const HeatMap& h : scan.heat_maps)
      if (!h.glb.empty()) files.push_back({folder / h.file, h.glb});
    for (const TexturedGlb& t : scan.textured)
      files.push_back({folder / t.file, t.glb});
    for (const Variant& v : scan.variants)
      if (!v.encoded.empty())
        files.push_back(
            {folder / "files" / detail::slug(scan.name) / (detail::slug(v.name) + v.extension), v.encoded});
  }
  return files;
}

Result<std::size_t> write_report(const Report& report, const std::filesystem::path& folder) {
  namespace fs = std::filesystem;
  const std::vector<OutputFile> files = report_files(report, folder);
  std::vector<fs::path> made; // the folders made here, innermost last
  const auto unmake = [&] {
    for (auto it = made.rbegin(); it != made.rend(); ++it) {
      std::error_code ec;
      fs::remove(*it, ec); // only if empty
    }
  };
  for (const OutputFile& f : files) {
    std::vector<fs::path> missing;
    for (fs::path dir = f.path.parent_path(); !dir.empty() && !fs::exists(dir); dir = dir.parent_path())
      missing.push_back(dir);
    for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
      std::error_code ec;
      if (!fs::create_directory(*it, ec) && ec) {
        unmake();
        return make_error(ErrorCode::Io, fmt::format("cannot make the folder: {}", ec.message()),
                          it->string());
      }
      made.push_back(*it);
    }
  }
  if (Result<void> written = write_files_atomic(files); !written) {
    unmake();
    return std::move(written).error();
  }
  return files.size();
}

} // namespace pdeface::pipeline

// The report as text: Markdown (tables per scan and a summary across scans), CSV and JSON.

#include "report_detail.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <limits>

namespace pdeface::pipeline {
namespace detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void add(Stat& s, double value, std::vector<double>& values) {
  if (!std::isfinite(value)) return;
  values.push_back(value);
  s.n = values.size();
}

Stat finish(const std::vector<double>& values) {
  Stat s{kNaN, 0.0, values.size()};
  if (values.empty()) return s;
  double sum = 0.0;
  for (double v : values)
    sum += v;
  s.mean = sum / static_cast<double>(values.size());
  if (values.size() > 1) {
    double squares = 0.0;
    for (double v : values)
      squares += (v - s.mean) * (v - s.mean);
    s.sd = std::sqrt(squares / static_cast<double>(values.size() - 1));
  }
  return s;
}

std::string number(double v, int digits = 3) {
  return std::isfinite(v) ? fmt::format("{:.{}f}", v, digits) : std::string("–");
}
std::string bytes_text(double b) {
  if (!std::isfinite(b)) return "–";
  if (b < 10'000) return fmt::format("{:.0f}", b);
  if (b < 10'000'000) return fmt::format("{:.1f} k", b / 1e3);
  return fmt::format("{:.2f} M", b / 1e6);
}
std::string ratio_text(double r) {
  if (!std::isfinite(r)) return "–";
  return r >= 0.1 ? fmt::format("{:.2f}", r) : fmt::format("1/{:.0f}", 1.0 / r);
}
std::string milliseconds(double ms) {
  return !std::isfinite(ms) ? std::string("–")
         : ms < 10          ? fmt::format("{:.1f}", ms)
                            : fmt::format("{:.0f}", ms);
}
std::string plus_minus(const Stat& s, const std::function<std::string(double)>& format,
                       const std::function<std::string(double)>& format_sd = {}) {
  if (s.n == 0) return "–";
  return s.n == 1 ? format(s.mean) : format(s.mean) + " ± " + (format_sd ? format_sd : format)(s.sd);
}

std::string cell_escape(const std::string& text) {
  std::string out;
  for (char c : text)
    out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

} // namespace

std::string slug(std::string_view text) {
  std::string out;
  for (char c : text) {
    if (std::isalnum(static_cast<unsigned char>(c)) != 0)
      out += c;
    else if (!out.empty() && out.back() != '-')
      out += '-';
  }
  while (!out.empty() && out.back() == '-')
    out.pop_back();
  return out;
}

std::vector<Aggregate> aggregate(const Report& report) {
  struct Values {
    std::vector<double> bytes, ratio, triangles, encode, decode, coverage, mask, to_scan, p95, max, profile;
  };
  std::vector<Aggregate> out;
  std::vector<Values> values;
  for (const ScanReport& scan : report.scans)
    for (const Variant& v : scan.variants) {
      auto it = std::ranges::find(out, v.name, &Aggregate::name);
      if (it == out.end()) {
        out.push_back({.name = v.name, .method = v.method});
        values.emplace_back();
        it = out.end() - 1;
      }
      Aggregate& a = *it;
      Values& x = values[static_cast<std::size_t>(it - out.begin())];
      if (!v.fidelity) continue;
      add(a.bytes, static_cast<double>(v.bytes), x.bytes);
      add(a.ratio_to_ply, v.ratio_to_ply, x.ratio);
      add(a.triangles, static_cast<double>(v.triangles), x.triangles);
      add(a.encode_ms, v.encode_ms, x.encode);
      add(a.decode_ms, v.decode_ms, x.decode);
      const metrics::MeshFidelity& f = *v.fidelity;
      add(a.coverage, 100.0 * f.coverage.share, x.coverage);
      add(a.mask_mean, f.coverage.distance.mean, x.mask);
      add(a.to_scan_mean, f.to_scan.mean, x.to_scan);
      add(a.to_scan_p95, f.to_scan.p95, x.p95);
      add(a.to_scan_max, f.to_scan.max, x.max);
      add(a.profile_error, f.mean_profile_error, x.profile);
    }
  for (std::size_t i = 0; i < out.size(); ++i) {
    Aggregate& a = out[i];
    const Values& x = values[i];
    a.bytes = finish(x.bytes);
    a.ratio_to_ply = finish(x.ratio);
    a.triangles = finish(x.triangles);
    a.encode_ms = finish(x.encode);
    a.decode_ms = finish(x.decode);
    a.coverage = finish(x.coverage);
    a.mask_mean = finish(x.mask);
    a.to_scan_mean = finish(x.to_scan);
    a.to_scan_p95 = finish(x.p95);
    a.to_scan_max = finish(x.max);
    a.profile_error = finish(x.profile);
  }
  return out;
}

std::string markdown(const Table& table) {
  std::string out = "|";
  for (const std::string& h : table.header)
    out += " " + cell_escape(h) + " |";
  out += "\n|";
  for (std::size_t c = 0; c < table.header.size(); ++c)
    out += c < table.right.size() && table.right[c] ? "---:|" : "---|";
  out += "\n";
  for (const auto& row : table.rows) {
    out += "|";
    for (const std::string& cell : row)
      out += " " + cell_escape(cell) + " |";
    out += "\n";
  }
  return out;
}

Table summary_table(const Report& report) {
  Table t{.header = {"variant", "scans", "bytes", "× PLY", "triangles", "coverage (%)", "mask → mesh mean",
                     "mesh → scan mean", "mesh → scan p95", "mesh → scan max", "profile error", "encode ms",
                     "decode ms"},
          .right = {false, true, true, true, true, true, true, true, true, true, true, true, true}};
  const auto f3 = [](double v) { return number(v); };
  for (const Aggregate& a : aggregate(report)) {
    if (a.bytes.n == 0) continue; // made for no scan: each scan's table says why
    t.rows.push_back(
        {a.name, fmt::format("{}", a.bytes.n), plus_minus(a.bytes, bytes_text),
         plus_minus(a.ratio_to_ply, ratio_text, [](double v) { return fmt::format("{:.2g}", v); }),
         plus_minus(a.triangles, [](double v) { return fmt::format("{:.0f}", v); }),
         plus_minus(a.coverage, [](double v) { return number(v, 1); }), plus_minus(a.mask_mean, f3),
         plus_minus(a.to_scan_mean, f3), plus_minus(a.to_scan_p95, f3), plus_minus(a.to_scan_max, f3),
         plus_minus(a.profile_error, f3), plus_minus(a.encode_ms, milliseconds),
         plus_minus(a.decode_ms, milliseconds)});
  }
  return t;
}

Table scan_table(const ScanReport& scan) {
  Table t{.header = {"variant", "bytes", "× PLY", "bits", "vertices", "triangles", "encode ms", "decode ms",
                     "coverage (%)", "mask → mesh mean", "mask → mesh p95", "mesh → scan mean", "RMS", "p95",
                     "max", "profile error"},
          .right = {false, true, true, true, true, true, true, true, true, true, true, true, true, true, true,
                    true}};
  for (const Variant& v : scan.variants) {
    if (!v.fidelity) { // nothing was made: the reason, no numbers
      std::vector<std::string> row{v.name, "–", "–", "–", "–", "–", "–", "–", "failed: " + v.failure};
      row.resize(t.header.size());
      t.rows.push_back(std::move(row));
      continue;
    }
    std::vector<std::string> row{v.name,
                                 fmt::format("{}", v.bytes),
                                 ratio_text(v.ratio_to_ply),
                                 v.bits > 0 ? fmt::format("{}", v.bits) : std::string("–"),
                                 fmt::format("{}", v.vertices),
                                 fmt::format("{}", v.triangles),
                                 milliseconds(v.encode_ms),
                                 milliseconds(v.decode_ms)};
    const metrics::MeshFidelity& f = *v.fidelity;
    for (const std::string& cell :
         {number(100.0 * f.coverage.share, 1), number(f.coverage.distance.mean),
          number(f.coverage.distance.p95), number(f.to_scan.mean), number(f.to_scan.rms),
          number(f.to_scan.p95), number(f.to_scan.max), number(f.mean_profile_error)})
      row.push_back(cell);
    t.rows.push_back(std::move(row));
  }
  return t;
}

std::string psnr_text(double db) { return std::isinf(db) ? std::string("∞") : number(db, 2); }

// The colour rows of a scan: bytes in parts, and the face's colours against the scan's.
Table colour_table(const ScanReport& scan) {
  Table t{.header = {"variant", "bytes", "geometry", "colour attributes", "image", "PSNR (dB)", "ΔE₀₀ mean",
                     "ΔE₀₀ p95", "mesh → scan mean"},
          .right = {false, true, true, true, true, true, true, true, true}};
  for (const Variant& v : scan.variants) {
    if (v.method != Method::DracoColour && v.method != Method::PdeTexture) continue;
    if (!v.colour) {
      std::vector<std::string> row{v.name, "–", "–", "–", "–", "failed: " + v.failure};
      row.resize(t.header.size());
      t.rows.push_back(std::move(row));
      continue;
    }
    const std::size_t geometry = v.bytes - v.image_bytes - v.attribute_bytes;
    t.rows.push_back({v.name, fmt::format("{}", v.bytes), fmt::format("{}", geometry),
                      v.attribute_bytes > 0 ? fmt::format("{}", v.attribute_bytes) : std::string("–"),
                      fmt::format("{}", v.image_bytes), psnr_text(v.colour->psnr_db),
                      number(v.colour->mean_delta_e, 2), number(v.colour->p95_delta_e, 2),
                      v.fidelity ? number(v.fidelity->to_scan.mean) : "–"});
  }
  return t;
}

// The colour rows across scans: mean bytes, PSNR and ΔE₀₀ of each (scans with colour only).
Table colour_summary_table(const Report& report) {
  Table t{.header = {"variant", "scans", "bytes", "image bytes", "PSNR (dB)", "ΔE₀₀ mean", "ΔE₀₀ p95"},
          .right = {false, true, true, true, true, true, true}};
  std::vector<std::string> names;
  for (const ScanReport& scan : report.scans)
    for (const Variant& v : scan.variants)
      if (v.colour && std::ranges::find(names, v.name) == names.end()) names.push_back(v.name);
  for (const std::string& name : names) {
    std::vector<double> bytes, image, psnr, mean, p95;
    for (const ScanReport& scan : report.scans)
      for (const Variant& v : scan.variants)
        if (v.name == name && v.colour) {
          bytes.push_back(static_cast<double>(v.bytes));
          image.push_back(static_cast<double>(v.image_bytes));
          if (std::isfinite(v.colour->psnr_db)) psnr.push_back(v.colour->psnr_db);
          mean.push_back(v.colour->mean_delta_e);
          p95.push_back(v.colour->p95_delta_e);
        }
    const auto f2 = [](double v) { return number(v, 2); };
    t.rows.push_back({name, fmt::format("{}", bytes.size()), plus_minus(finish(bytes), bytes_text),
                      plus_minus(finish(image), bytes_text), plus_minus(finish(psnr), f2),
                      plus_minus(finish(mean), f2), plus_minus(finish(p95), f2)});
  }
  return t;
}

std::string scan_heading(const ScanReport& scan) {
  if (!scan.failure.empty()) return fmt::format("{}: failed", scan.name);
  return fmt::format(
      "{}: {}{} vertices, {} triangles, units {}{} ({:.1f} s)", scan.name,
      scan.face_only ? "the face cropped, " : "", scan.vertices, scan.triangles, to_string(scan.units),
      scan.units_per_mm != 1.0 ? fmt::format(", 1 mm = {:.4g} scan units", scan.units_per_mm) : std::string(),
      scan.seconds);
}

std::string method_notes(const Report& report) {
  const CompareOptions& o = report.options;
  return fmt::format(
      "Every variant but the colour rows holds the scan's geometry only (positions and triangles; its "
      "normals, colours and texture coordinates are left out of them alike) and is measured on what decoding "
      "its bytes gives back. Distances are in mm in the canonical face frame (the scan's geometry at its own "
      "scale, "
      "in mm), sampled every {:g} mm on each surface:\n"
      "- **coverage**: the share of the scan's face (its front-most surface inside the face mask its "
      "landmarks outline: an ellipse from the chin to the forehead, across the cheeks just beyond the outer "
      "eye corners) within {:g} mm of the variant; **mask → mesh**: those samples' distances to the variant "
      "(mean, 95th percentile).\n"
      "- **mesh → scan**: the variant's samples inside the mask, where the scan has surface, to the scan "
      "(mean, RMS, 95th percentile, max).\n"
      "- **profile error**: the paper's Table I measure on the 4 evaluation profiles (symmetry, eyes, two "
      "diagonals through the nose tip), mean of the four.\n"
      "- **bytes**: of the file as written (k = 1000, M = 10⁶ in the summary); **× PLY**: against the raw "
      "binary PLY; **encode / decode ms**: "
      "one run on one core of this machine (decimate + Draco: simplifying and encoding the row's mesh; the "
      "search for it is not counted). Draco at level {}; decimate + Draco: meshoptimizer's simplifier to "
      "the most triangles whose Draco bytes land within {:g} % under the budget, for each of {} bits, "
      "keeping the bits of least error; gzip at level {}.\n"
      "- Heat maps: each vertex's distance to the scan, 0 mm blue to {:g} mm red (and beyond), grey outside "
      "the face mask.\n"
      "- **Colour** (scans that have it: a photograph with texture coordinates, or vertex colours): Draco "
      "with the texture coordinates ({} bits; vertex colours: {} bits) beside the photograph (its own file, "
      "and resized to a share of its size as JPEG q{}), and the `.pdef` with a texture layer (texel mm, JPEG "
      "quality); bytes are the whole (file and photograph), split into geometry, colour attributes and "
      "image. Measured on the scan's face every {:g} mm inside the mask: the colour of each point on the "
      "scan against the variant's at its nearest point, as 8-bit sRGB: **PSNR** over R, G and B, and "
      "**ΔE₀₀** (CIEDE2000 in CIELAB; ~1 is just noticeable). Textured GLBs of these rows beside the heat "
      "maps.\n",
      o.fidelity.sample_spacing_mm, o.fidelity.covered_within_mm, o.draco_level, 100.0 * o.budget_slack,
      fmt::join(o.decimate_bits, ", "), o.gzip_level, o.heat_max_mm, o.draco_uv_bits, o.draco_color_bits,
      o.photo_quality, o.colour_spacing_mm);
}

} // namespace detail

std::string report_markdown(const Report& report) {
  std::string out = "# pdeface compare: size and fidelity\n\n";
  out += fmt::format("{} scan{} ({} failed), {:.1f} s.\n\n", report.scans.size(),
                     report.scans.size() == 1 ? "" : "s", report.failed(), report.seconds);
  out += detail::method_notes(report);
  out += "\n## Summary across scans (mean ± sd)\n\n" + detail::markdown(detail::summary_table(report));
  if (const detail::Table colour = detail::colour_summary_table(report); !colour.rows.empty())
    out += "\n## Colour across scans (mean ± sd; scans with colour)\n\n" + detail::markdown(colour);
  if (const detail::Table rd = detail::rd_summary_table(report); !rd.rows.empty())
    out += "\n## Rate and distortion: `.pdef` with a residual layer against decimate + Draco (mesh → scan, "
           "mm)\n\n" +
           detail::markdown(rd);
  for (const ScanReport& scan : report.scans) {
    out += "\n## " + detail::scan_heading(scan) + "\n\n";
    if (!scan.failure.empty()) {
      out += scan.failure + "\n";
      continue;
    }
    out += fmt::format("Raw binary PLY: {} bytes.\n\n", scan.ply_bytes) +
           detail::markdown(detail::scan_table(scan));
    if (const detail::Table rd = detail::rd_scan_table(scan); !rd.rows.empty())
      out += "\nRate and distortion (mesh → scan, mm):\n\n" + detail::markdown(rd);
    if (const detail::Table colour = detail::colour_table(scan); !colour.rows.empty())
      out += fmt::format("\nColour (the scan's {}; face mask):\n\n",
                         scan.colour == metrics::ColourSource::Texture ? "photograph" : "vertex colours") +
             detail::markdown(colour);
    if (!scan.heat_maps.empty()) {
      out += "\nHeat maps (GLB, canonical frame, mm):";
      for (const HeatMap& h : scan.heat_maps)
        out += fmt::format(" [{}]({})", h.variant, h.file);
      out += "\n";
    }
    if (!scan.textured.empty()) {
      out += "\nTextured (GLB, canonical frame, mm):";
      for (const TexturedGlb& t : scan.textured)
        out += fmt::format(" [{}]({})", t.variant, t.file);
      out += "\n";
    }
  }
  return out;
}

namespace {

std::string csv_number(double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : std::string(); }
std::string csv_quoted(std::string_view text) {
  std::string q = "\"";
  for (char c : text)
    q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

} // namespace

std::string report_csv(const Report& report) {
  std::string out =
      "scan,units,method,variant,bits,budget,ratio,lossless,bytes,ratio_to_ply,encode_ms,decode_ms,vertices,"
      "triangles,coverage,mask_mean_mm,mask_rms_mm,mask_p95_mm,mask_max_mm,to_scan_mean_mm,to_scan_rms_mm,"
      "to_scan_p95_mm,to_scan_max_mm,profile_symmetry_mm,profile_eyes_mm,profile_diagonal_up_mm,"
      "profile_diagonal_down_mm,profile_mean_mm,image_bytes,attribute_bytes,psnr_db,delta_e_mean,delta_e_p95,"
      "failure\n";
  for (const ScanReport& scan : report.scans) {
    if (!scan.failure.empty()) {
      out += fmt::format("{},,,,,,,,,,,,,,,,,,,,,,,,,,,,,,,,,{}\n", csv_quoted(scan.name),
                         csv_quoted(scan.failure));
      continue;
    }
    for (const Variant& v : scan.variants) {
      out += fmt::format(
          "{},{},{},{},{},{},{},{},{},{},{},{},{},{},", csv_quoted(scan.name), to_string(scan.units),
          to_string(v.method), csv_quoted(v.name), v.bits > 0 ? fmt::format("{}", v.bits) : "",
          v.budget > 0 ? fmt::format("{}", v.budget) : "", v.ratio > 0 ? fmt::format("{:g}", v.ratio) : "",
          v.lossless ? 1 : 0, v.bytes, csv_number(v.ratio_to_ply), csv_number(v.encode_ms),
          csv_number(v.decode_ms), v.vertices, v.triangles);
      const std::string colour =
          !v.colour ? std::string(",,,,,")
                    : fmt::format("{},{},{},{},{},", v.image_bytes, v.attribute_bytes,
                                  std::isinf(v.colour->psnr_db) ? std::string("inf")
                                                                : csv_number(v.colour->psnr_db),
                                  csv_number(v.colour->mean_delta_e), csv_number(v.colour->p95_delta_e));
      if (v.fidelity) {
        const metrics::MeshFidelity& f = *v.fidelity;
        const metrics::DistanceStats& m = f.coverage.distance;
        out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", csv_number(f.coverage.share),
                           csv_number(m.mean), csv_number(m.rms), csv_number(m.p95), csv_number(m.max),
                           csv_number(f.to_scan.mean), csv_number(f.to_scan.rms), csv_number(f.to_scan.p95),
                           csv_number(f.to_scan.max), csv_number(f.profile_error[0]),
                           csv_number(f.profile_error[1]), csv_number(f.profile_error[2]),
                           csv_number(f.profile_error[3]), csv_number(f.mean_profile_error), colour);
      } else {
        out += std::string(14, ',') + colour + csv_quoted(v.failure) + "\n";
      }
    }
  }
  return out;
}

std::string report_json(const Report& report) {
  using nlohmann::json;
  const auto stats = [](const metrics::DistanceStats& d) {
    const auto n = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
    return json{
        {"mean", n(d.mean)}, {"rms", n(d.rms)}, {"p95", n(d.p95)}, {"max", n(d.max)}, {"samples", d.samples}};
  };
  const CompareOptions& o = report.options;
  json doc{{"format", "pdeface-compare"},
           {"version", 1},
           {"distance_units", "mm"},
           {"seconds", report.seconds},
           {"options",
            {{"draco_bits", o.draco_bits},
             {"draco_level", o.draco_level},
             {"budgets", o.budgets},
             {"decimate_bits", o.decimate_bits},
             {"budget_slack", o.budget_slack},
             {"ratios", o.ratios},
             {"scheme", pde::to_string(o.scheme)},
             {"gzip_level", o.gzip_level},
             {"sample_spacing_mm", o.fidelity.sample_spacing_mm},
             {"covered_within_mm", o.fidelity.covered_within_mm},
             {"heat_max_mm", o.heat_max_mm}}},
           {"scans", json::array()}};
  for (const ScanReport& scan : report.scans) {
    json s{{"name", scan.name}, {"source", scan.source}};
    if (!scan.failure.empty()) {
      s["failure"] = scan.failure;
      doc["scans"].push_back(std::move(s));
      continue;
    }
    s.update({{"units", to_string(scan.units)},
              {"units_per_mm", scan.units_per_mm},
              {"vertices", scan.vertices},
              {"triangles", scan.triangles},
              {"face_only", scan.face_only},
              {"ply_bytes", scan.ply_bytes},
              {"seconds", scan.seconds},
              {"heat_maps", json::array()},
              {"variants", json::array()}});
    for (const HeatMap& h : scan.heat_maps)
      s["heat_maps"].push_back({{"variant", h.variant}, {"file", h.file}, {"scale_mm", h.scale_mm}});
    s["textured"] = json::array();
    for (const TexturedGlb& t : scan.textured)
      s["textured"].push_back({{"variant", t.variant}, {"file", t.file}});
    s["colour"] = scan.colour == metrics::ColourSource::Texture         ? "photograph"
                  : scan.colour == metrics::ColourSource::VertexColours ? "vertex colours"
                                                                        : "none";
    for (const Variant& v : scan.variants) {
      json j{{"method", to_string(v.method)},  {"name", v.name},
             {"extension", v.extension},       {"bytes", v.bytes},
             {"ratio_to_ply", v.ratio_to_ply}, {"encode_ms", v.encode_ms},
             {"decode_ms", v.decode_ms},       {"vertices", v.vertices},
             {"triangles", v.triangles},       {"lossless", v.lossless}};
      if (v.bits > 0) j["bits"] = v.bits;
      if (v.budget > 0) j["budget"] = v.budget;
      if (v.ratio > 0) j["ratio"] = v.ratio;
      if (v.colour) {
        j["image_bytes"] = v.image_bytes;
        j["attribute_bytes"] = v.attribute_bytes;
        j["colour"] = {{"psnr_db", std::isfinite(v.colour->psnr_db) ? json(v.colour->psnr_db) : json("inf")},
                       {"delta_e2000_mean", v.colour->mean_delta_e},
                       {"delta_e2000_p95", v.colour->p95_delta_e},
                       {"samples", v.colour->samples},
                       {"uncoloured", v.colour->uncoloured}};
      }
      if (v.fidelity) {
        const metrics::MeshFidelity& f = *v.fidelity;
        json profile = json::array();
        for (double e : f.profile_error)
          profile.push_back(std::isfinite(e) ? json(e) : json(nullptr));
        j["fidelity"] = {{"coverage", f.coverage.share},
                         {"mask_to_mesh", stats(f.coverage.distance)},
                         {"mesh_to_scan", stats(f.to_scan)},
                         {"profile_error", profile},
                         {"mean_profile_error",
                          std::isfinite(f.mean_profile_error) ? json(f.mean_profile_error) : json(nullptr)}};
      } else {
        j["failure"] = v.failure;
      }
      s["variants"].push_back(std::move(j));
    }
    doc["scans"].push_back(std::move(s));
  }
  return doc.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n"; // names: any bytes
}

} // namespace pdeface::pipeline

#pragma once
// What the report's documents share: the variants averaged over the scans, and tables that print as
// Markdown or HTML alike.

#include "pdeface/pipeline/report.hpp"

#include <string>
#include <vector>

namespace pdeface::pipeline::detail {

//! A mean and a sample standard deviation over the scans (sd 0 for one scan; NaN mean for none).
struct Stat {
  double mean = 0.0;
  double sd = 0.0;
  std::size_t n = 0;
};

//! One variant (by name) over every scan that has it measured.
struct Aggregate {
  std::string name;
  Method method = Method::Raw;
  Stat bytes, ratio_to_ply, triangles, encode_ms, decode_ms;
  Stat coverage, mask_mean, to_scan_mean, to_scan_p95, to_scan_max, profile_error;
};
//! The variants in the order they first appear.
[[nodiscard]] std::vector<Aggregate> aggregate(const Report& report);

struct Table {
  std::vector<std::string> header;
  std::vector<bool> right; //!< per column: numbers, aligned right
  std::vector<std::vector<std::string>> rows;
};
[[nodiscard]] std::string markdown(const Table& table);
[[nodiscard]] std::string html(const Table& table);

//! The summary across scans (mean ± sd per variant) and one scan's rows.
[[nodiscard]] Table summary_table(const Report& report);
[[nodiscard]] Table scan_table(const ScanReport& scan);
//! The colour rows of a scan, and across scans (issue 20).
[[nodiscard]] Table colour_table(const ScanReport& scan);
[[nodiscard]] Table colour_summary_table(const Report& report);
//! The `.pdef` with a residual layer against decimate + Draco at each byte budget (mesh → scan mean, p95,
//! max): one scan's, and across scans (the median scan and the worst).
[[nodiscard]] Table rd_scan_table(const ScanReport& scan);
[[nodiscard]] Table rd_summary_table(const Report& report);

//! A file-name-safe form of `text`: letters and digits, runs of anything else as one '-'.
[[nodiscard]] std::string slug(std::string_view text);

//! Words the documents share: what the figures are, and the heat maps' scale.
[[nodiscard]] std::string method_notes(const Report& report);
[[nodiscard]] std::string scan_heading(const ScanReport& scan);

} // namespace pdeface::pipeline::detail

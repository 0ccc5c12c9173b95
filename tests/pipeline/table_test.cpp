// Table I rows on the sample face, and their Markdown and CSV.

#include "pdeface/core/sample_face.hpp"
#include "pdeface/pipeline/table.hpp"

#include "pdeface_test.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace pdeface::pipeline {
namespace {

// Computed once per process: the Table suite runs in one process (tests/CMakeLists.txt).
const std::vector<TableRow>& rows() {
  static const std::vector<TableRow> r = [] {
    const Mesh face = sample_face();
    const align::Alignment a = align::align_scan(face, std::nullopt).value();
    TableOptions options{.ratios = {0.05, 0.1, 0.3}};
    return table_rows(face, a, options, "sample.ply").value();
  }();
  return r;
}

using test::split;

TEST(Table, OneRowPerRatioAndScheme) {
  ASSERT_EQ(rows().size(), 9U);
  for (std::size_t i = 0; i < 9; ++i) {
    const TableRow& r = rows()[i];
    EXPECT_EQ(r.scan, "sample.ply");
    EXPECT_EQ(r.ratio, (std::array{0.05, 0.1, 0.3})[i / 3]);
    EXPECT_EQ(r.scheme, (std::array{pde::Scheme::Spline, pde::Scheme::Paper, pde::Scheme::Patch4})[i % 3]);
    ASSERT_TRUE(r.fidelity) << r.failure;
    EXPECT_GT(r.k, 4U);
    EXPECT_GT(r.smoothing, 0.0);
    for (double e : r.fidelity->profile_error)
      EXPECT_TRUE(std::isfinite(e));
    EXPECT_TRUE(std::isfinite(r.fidelity->curve_error)) << i; // the border curves are measured too
  }
  // More points per curve, smaller profile error for the spline.
  EXPECT_GT(rows()[0].fidelity->mean_profile_error, rows()[3].fidelity->mean_profile_error);
  EXPECT_GE(rows()[3].fidelity->mean_profile_error, rows()[6].fidelity->mean_profile_error * 0.9);
  EXPECT_LT(rows()[0].k, rows()[3].k);
  EXPECT_LT(rows()[3].k, rows()[6].k);
}

TEST(Table, MarkdownHasTheSummariesAndEveryRow) {
  const std::string md = table_markdown(rows());
  for (const char* heading :
       {"## Profile error (mm)", "## Profile error on the curves' own planes (mm)",
        "## Surface distance, mean (mm)", "## Surface distance, 95th percentile (mm)",
        "## Face coverage: share of the scan's face mask within 1 mm of the reconstruction (%)",
        "## Face mask: scan to reconstruction, mean (mm)", "## Every scan"})
    EXPECT_NE(md.find(heading), std::string::npos) << heading;
  EXPECT_NE(md.find("| ratio | K | spline | paper | patch4 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 10 % |"), std::string::npos) << md;
  const auto lines = split(md, '\n');
  const auto count =
      std::ranges::count_if(lines, [](const std::string& l) { return l.starts_with("| sample.ply"); });
  EXPECT_EQ(count, 9);
  // Every table line has as many cells as its header.
  std::size_t cells = 0;
  for (const std::string& l : lines) {
    if (!l.starts_with("|")) {
      cells = 0;
      continue;
    }
    const auto n = static_cast<std::size_t>(std::ranges::count(l, '|'));
    if (cells == 0) cells = n;
    EXPECT_EQ(n, cells) << l;
  }
}

TEST(Table, CsvHasAHeaderAndOneLinePerRow) {
  const auto lines = split(table_csv(rows()), '\n');
  ASSERT_EQ(lines.size(), 10U);
  const std::size_t columns = split(lines[0], ',').size();
  EXPECT_EQ(columns, 20U);
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const auto cells = split(lines[i] + ",", ','); // a trailing empty cell is still a cell
    EXPECT_EQ(cells.size(), columns) << lines[i];
    EXPECT_EQ(cells[0], "\"sample.ply\"");
    EXPECT_NEAR(std::stod(cells[10]), rows()[i - 1].fidelity->mean_profile_error, 1e-5);
    EXPECT_NEAR(std::stod(cells[17]), rows()[i - 1].fidelity->coverage.share, 1e-5);
  }
}

TEST(Table, AFailedSchemeIsARowThatSaysWhy) {
  const Mesh face = sample_face();
  const align::Alignment a = align::align_scan(face, std::nullopt).value();
  TableOptions options{.ratios = {0.1}, .schemes = {pde::Scheme::Patch4}};
  options.pde.smoothing = 1000.0; // patch4 cannot take a single mode stably
  const Result<std::vector<TableRow>> r = table_rows(face, a, options, "sample.ply");
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_EQ(r->size(), 1U);
  EXPECT_FALSE((*r)[0].fidelity);
  EXPECT_NE((*r)[0].failure.find("patch4"), std::string::npos) << (*r)[0].failure;
  const std::string md = table_markdown(*r);
  EXPECT_NE(md.find("failed: patch4"), std::string::npos) << md;
  const auto csv = split(table_csv(*r), '\n');
  ASSERT_EQ(csv.size(), 2U);
  EXPECT_NE(csv[1].find(",,,,,,,,,,,,,,,\"patch4"), std::string::npos) << csv[1];

  options.ratios = {0.9};
  const Result<std::vector<TableRow>> bad = table_rows(face, a, options, "sample.ply");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().source, "sample.ply");
}

} // namespace
} // namespace pdeface::pipeline

#pragma once
//! \file
//! The paper's Table I on any scans: profile error per sampling ratio and scheme, with the surface
//! distances beside it.

#include "pdeface/align/detect.hpp"
#include "pdeface/metrics/fidelity.hpp"
#include "pdeface/pde/surface.hpp"
#include "pdeface/slice/profiles.hpp"

#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace pdeface::pipeline {

//! The sampling ratios of the paper's Table I.
inline constexpr std::array<double, 8> kPaperRatios{0.05, 0.10, 0.15, 0.20, 0.25, 0.30, 0.50, 0.60};

struct TableOptions {
  std::vector<double> ratios{kPaperRatios.begin(), kPaperRatios.end()};
  std::vector<pde::Scheme> schemes{pde::Scheme::Spline, pde::Scheme::Paper, pde::Scheme::Patch4};
  slice::ProfileOptions profiles; //!< its ratio is each of `ratios` in turn
  //! Its scheme is each of `schemes` in turn; `Patch4` gets at most `pde::max_modes` modes (so a row is
  //! the most of the curves patch4 can use stably, not a refusal).
  pde::Options pde{.spacing = pde::Spacing::Physical};
  metrics::FidelityOptions fidelity;
  double grid_spacing_mm = 1.0; //!< the surfaces are measured as meshes of about this spacing
};

//! One scan at one ratio with one scheme.
struct TableRow {
  std::string scan;
  double ratio = 0.0;
  std::size_t k = 0; //!< points per curve
  pde::Scheme scheme = pde::Scheme::Spline;
  std::size_t modes = 0;  //!< N used
  double smoothing = 0.0; //!< a used
  std::optional<metrics::Fidelity> fidelity;
  std::string failure; //!< why there is no fidelity (the scheme could not be built or measured)
};

//! Every ratio × scheme of `options` on one scan. A scheme that fails gives a row with `failure` set.
//! Errors: the scan cannot be sliced at some ratio (`slice::extract_profiles`), `source` set.
[[nodiscard]] Result<std::vector<TableRow>> table_rows(const Mesh& scan, const align::Alignment& alignment,
                                                       const TableOptions& options = {},
                                                       std::string_view source = {});

//! Markdown: the profile error and the two-sided surface distance (mean and 95th percentile), each as
//! ratio × scheme averaged over the scans, then every row in full. Units: mm.
[[nodiscard]] std::string table_markdown(std::span<const TableRow> rows);

//! CSV with a header line, one line per row, every figure in mm (empty when the row failed).
[[nodiscard]] std::string table_csv(std::span<const TableRow> rows);

} // namespace pdeface::pipeline

// A `.pdef` file's residual layer (version 3): the scan's offsets from the decoded curves' surface,
// measured on a grid, coded, and cut to a size or to the fewest bytes that meet a measured error.

#include "encode_residual.hpp"
#include "pdeface/pipeline/encode.hpp"

#include "pdeface/pdef/mesh.hpp"
#include "pdeface/pdef/residual.hpp"
#include "pdeface/residual/measure.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>

namespace pdeface::pipeline {
namespace {

// 1 mm below 6 KB of layer, 0.5 mm below 12 KB, 0.35 mm above: the finer grid follows the creases and
// folds a coarser one cuts, where the surface's normals cross before they reach the scan (at 8 KB the
// 0.7 mm grid it replaced left the worst point up to twice as far off, 1.5x at the median scan, for a mean
// within 5 %; docs/compare.md, "The residual layer"); a point cloud's surface between its points is its
// tangent planes' model, which a grid finer than 0.5 mm only follows into their noise.
double spacing_for(const ResidualRequest& request, std::size_t curves, bool cloud) {
  if (request.spacing_mm) return *request.spacing_mm;
  if (!request.size_bytes) return 0.7;
  const std::size_t layer = *request.size_bytes > curves ? *request.size_bytes - curves : 0;
  return layer < 6000 ? 1.0 : layer < 12000 || cloud ? 0.5 : 0.35;
}

double statistic(const metrics::MeshFidelity& f, TargetMeasure measure) {
  switch (measure) {
  case TargetMeasure::Mean: return f.to_scan.mean;
  case TargetMeasure::Max: return f.to_scan.max;
  case TargetMeasure::P95: break;
  }
  return f.to_scan.p95;
}

} // namespace

metrics::CheckLimits with_scans_folds(metrics::CheckLimits limits, const Mesh& scan,
                                      const slice::FaceMask& mask) {
  limits.max_facing_away += metrics::facing_away(scan, mask);
  return limits;
}

Result<ResidualOutcome> add_residual(const CanonicalScan& scan, EncodeOutcome& outcome,
                                     const ResidualRequest& request, std::string_view source,
                                     ResidualGrids* grids) {
  const std::string curves = outcome.encoded.bytes;
  if (request.size_bytes && *request.size_bytes < curves.size())
    return make_error(
        ErrorCode::InvalidArgument,
        fmt::format("{} bytes cannot hold the curves alone ({} bytes at this ratio): ask for more "
                    "or a smaller ratio",
                    *request.size_bytes, curves.size()),
        std::string(source));
  // The offsets are from the surface a reader decodes (the lossy curves'), not the original curves'.
  Result<pdef::Face> face = pdef::decode(curves, source);
  if (!face) return std::move(face).error();
  Result<pde::Surface> surface = pdef::surface_of(*face, source);
  if (!surface) return std::move(surface).error();
  ResidualOutcome out;
  const double asked = spacing_for(request, curves.size(), scan.mesh.is_point_cloud());
  const ResidualGrids::Grid* made_grid = nullptr;
  ResidualGrids::Grid own;
  if (grids)
    if (const auto found = grids->by_spacing.find(asked); found != grids->by_spacing.end())
      made_grid = &found->second;
  if (!made_grid) {
    const auto start = std::chrono::steady_clock::now();
    own.spacing_mm = asked;
    residual::GridSize grid = residual::grid_for(*surface, own.spacing_mm);
    const std::size_t most = pdef::max_residual_nodes(curves.size());
    while (grid.width * grid.height > most) { // a bust's long, steep sides: coarser
      own.spacing_mm *= 1.1;
      grid = residual::grid_for(*surface, own.spacing_mm);
    }
    const residual::Measured measured = residual::measure(*surface, scan.mesh, grid.width, grid.height);
    // Cells with no scan under them: off it by a fifth of the grid's spacing (what the grid resolves).
    const std::vector<std::uint8_t> trimmed =
        residual::trim(*surface, scan.mesh, measured, {.off_scan_mm = own.spacing_mm / 5});
    Result<pdef::CodedResidual> coded =
        pdef::code_residual(residual::kept_field(measured, trimmed), {.max_nodes = most});
    if (!coded) return std::move(coded).error();
    coded->trim = pdef::code_trim(trimmed, grid.width, grid.height);
    own.trimmed_share =
        static_cast<double>(std::ranges::count(trimmed, 1)) / static_cast<double>(trimmed.size());
    own.width = grid.width;
    own.height = grid.height;
    own.found_share = measured.found_share();
    own.coded = *std::move(coded);
    own.made_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    made_grid = grids ? &(grids->by_spacing[asked] = std::move(own)) : &own;
  }
  const pdef::CodedResidual* coded = &made_grid->coded;
  out.spacing_mm = made_grid->spacing_mm;
  out.width = made_grid->width;
  out.height = made_grid->height;
  out.found_share = made_grid->found_share;
  out.whole_stream = coded->stream.size();
  // The trim whole when it takes at most half the layer, else none: the first bytes of the offsets remove
  // more error than a trim cut short, and a trim, where it is needed at all, removes the worst points (open
  // nostrils bridged 3-4 mm off; docs/compare.md, "The residual layer").
  const auto trim_for = [&](std::size_t bytes) {
    const std::size_t layer = bytes > curves.size() ? bytes - curves.size() : 0;
    return 2 * coded->trim.size() <= layer ? coded->trim.size() : 0;
  };
  const std::size_t smallest = curves.size() + pdef::residual_header(*coded, 0, 0).size();
  const std::size_t largest = curves.size() + pdef::residual_header(*coded, coded->stream.size()).size() +
                              coded->trim.size() + coded->stream.size();
  std::size_t trim_bytes = 0; // in the file made last
  auto file_of = [&](std::size_t bytes) {
    trim_bytes = trim_for(bytes);
    return pdef::with_residual(curves, *coded, bytes, {.trim_bytes = trim_bytes});
  };
  std::string file;
  if (request.size_bytes) {
    if (*request.size_bytes < smallest) { // room for the curves, not the layer's header: curves alone
      out.layer_bytes = 0;
      return out;
    }
    Result<std::string> made = file_of(std::min(*request.size_bytes, largest));
    if (!made) return std::move(made).error();
    file = *std::move(made);
  } else {
    // The fewest bytes that meet the target, measured as `pdeface compare` measures: the file decoded,
    // meshed in the scan's frame, back in the canonical frame, against the scan on its face mask.
    Result<slice::ProfileSet> profiles = extract_profiles(scan);
    if (!profiles) return std::move(profiles).error();
    Result<metrics::FaceYardstick> yardstick = metrics::FaceYardstick::make(scan.mesh, *profiles);
    if (!yardstick) return std::move(yardstick).error();
    auto measure = [&](std::size_t bytes) -> Result<metrics::MeshFidelity> {
      Result<std::string> made = file_of(bytes);
      if (!made) return std::move(made).error();
      Result<pdef::Face> decoded = pdef::decode(*made, source);
      if (!decoded) return std::move(decoded).error();
      Result<Mesh> mesh = pdef::to_mesh(*decoded, std::nullopt, source);
      if (!mesh) return std::move(mesh).error();
      return yardstick->measure(align::to_canonical(*std::move(mesh), outcome.alignment.frame));
    };
    const double target = *request.target_error_mm;
    Result<metrics::MeshFidelity> best = measure(largest);
    if (!best) return std::move(best).error();
    if (statistic(*best, request.target_measure) > target)
      return make_error(
          ErrorCode::SelfCheck,
          fmt::format("the whole residual layer ({} bytes) reaches {} {:.4f} mm, not {:.4f} mm: "
                      "the target cannot be met at this grid ({} mm)",
                      largest, name_of<TargetMeasure>(kTargetMeasureNames, request.target_measure),
                      statistic(*best, request.target_measure), target, out.spacing_mm),
          std::string(source));
    std::size_t low = smallest, high = largest; // high meets the target; search the fewest bytes that do
    while (high - low > std::max<std::size_t>(8, high / 200)) {
      const std::size_t mid = low + (high - low) / 2;
      Result<metrics::MeshFidelity> f = measure(mid);
      if (!f) return std::move(f).error();
      if (statistic(*f, request.target_measure) <= target) {
        high = mid;
        best = *std::move(f);
      } else {
        low = mid;
      }
    }
    Result<std::string> made = file_of(high);
    if (!made) return std::move(made).error();
    file = *std::move(made);
    out.measured = *best;
  }
  out.layer_bytes = file.size() - curves.size();
  out.trim_bytes = trim_bytes;
  out.trimmed_share = out.trim_bytes > 0 ? made_grid->trimmed_share : 0.0;
  outcome.encoded.bytes = std::move(file);
  return out;
}

} // namespace pdeface::pipeline

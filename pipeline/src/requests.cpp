#include "pdeface/pipeline/requests.hpp"

#include "pdeface/pipeline/preview.hpp"
#include "pdeface/slice/output.hpp"

#include <fmt/format.h>

#include <filesystem>

namespace pdeface::pipeline {
namespace {

std::string file_name(std::string_view source) { return std::filesystem::path(source).filename().string(); }

} // namespace

Result<ProfilesOutcome> profiles_request(const Mesh& scan, const ProfilesRequest& request) {
  Result<align::Alignment> alignment = align::align_from(scan, request.landmarks, request.source);
  if (!alignment) return alignment.error();
  const CanonicalScan canonical = canonical_scan(scan, *alignment);
  Result<slice::ProfileSet> set = extract_profiles(canonical, request.profiles);
  if (!set) return with_source(std::move(set).error(), request.source);
  ProfilesOutcome out{*alignment, *std::move(set), {}, {}};
  out.json = slice::write_profiles_json(out.profiles);
  if (request.svg)
    out.svg = slice::profiles_svg(
        canonical.mesh, out.profiles,
        {.title = fmt::format("{}: {} curves, K = {} ({:.1f} % of {} reference points), {}",
                              file_name(request.source), out.profiles.curves.size(), out.profiles.k,
                              100.0 * out.profiles.ratio, out.profiles.reference_points,
                              slice::to_string(out.profiles.parameter))});
  return out;
}

Result<ReconstructOutcome> reconstruct_request(const Mesh& scan, const ReconstructRequest& request) {
  Result<align::Alignment> alignment = align::align_from(scan, request.landmarks, request.source);
  if (!alignment) return alignment.error();
  const CanonicalScan canonical = canonical_scan(scan, *alignment);
  Result<Reconstruction> made = reconstruct(canonical, request.options, request.source);
  if (!made) return made.error();
  ReconstructOutcome out{.alignment = *alignment,
                         .reconstruction = *std::move(made),
                         .scan_units_per_mm = 1.0 / canonical.frame.scale};
  const Reconstruction& r = out.reconstruction;
  if (Result<metrics::Fidelity> f = metrics::measure_fidelity(canonical.mesh, r.profiles, r.canonical))
    out.fidelity = *f;
  else
    out.fidelity_failure = f.error().message;
  Result<metrics::SelfCheck> check =
      metrics::checked(canonical.mesh, r.profiles, r.canonical, request.check, request.force, request.source);
  if (!check) return check.error();
  out.check = *std::move(check);
  if (request.profiles_json) out.profiles_json = slice::write_profiles_json(r.profiles);
  if (request.preview)
    out.preview_svg = reconstruction_preview_svg(
        canonical.mesh, r.canonical, r.profiles,
        {.title = fmt::format("{}: {} curves x {} points", file_name(request.source),
                              r.profiles.curves.size(), r.profiles.k)});
  return out;
}

Result<std::vector<TableRow>> table_request(const Mesh& scan, const TableOptions& options,
                                            std::string_view source) {
  // Like the rows, detection spreads over every core.
  Result<align::Alignment> alignment = align::align_scan(scan, std::nullopt, source, {}, {.threads = 0});
  if (!alignment) return alignment.error();
  Result<std::vector<TableRow>> rows = table_rows(scan, *alignment, options, file_name(source));
  if (!rows) {
    Error e = std::move(rows).error();
    e.source = source; // the path as given, not the row's name
    return e;
  }
  return rows;
}

} // namespace pdeface::pipeline

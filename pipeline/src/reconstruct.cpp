#include "pdeface/pipeline/reconstruct.hpp"

#include "pdeface/align/frame.hpp"

#include <algorithm>

namespace pdeface::pipeline {
namespace {

double width(const slice::ProfileSet& p) { return p.border[0] + p.border[1]; }
double height(const slice::ProfileSet& p) { return p.height_range[1] - p.height_range[0]; }

} // namespace

CanonicalScan canonical_scan(Mesh scan, const align::Alignment& alignment) {
  return {align::to_canonical(std::move(scan), alignment.frame),
          align::to_canonical(alignment.landmarks, alignment.frame), alignment.frame};
}

Result<slice::ProfileSet> extract_profiles(const CanonicalScan& scan, const slice::ProfileOptions& options) {
  return slice::extract_profiles(scan.mesh, scan.landmarks, scan.frame, options);
}

pde::Curves to_curves(const slice::ProfileSet& profiles) {
  pde::Curves curves;
  curves.units = Units::Millimetres;
  curves.samples.reserve(profiles.curves.size());
  for (const slice::ProfileCurve& c : profiles.curves) {
    pde::Curve samples(static_cast<Eigen::Index>(c.points.size()), 3);
    for (std::size_t k = 0; k < c.points.size(); ++k)
      samples.row(static_cast<Eigen::Index>(k)) = c.points[k].transpose();
    curves.samples.push_back(std::move(samples));
  }
  return curves;
}

Resolution resolution_for(const slice::ProfileSet& profiles, double spacing_mm) {
  return pdef::grid_for(width(profiles), height(profiles), spacing_mm);
}

Resolution resolution_for(const slice::ProfileSet& profiles, std::size_t v) {
  return pdef::grid_for(width(profiles), height(profiles), v);
}

Result<pde::Surface> surface_from(const slice::ProfileSet& profiles, const pde::Options& options,
                                  std::string_view source) {
  return pde::Surface::build(to_curves(profiles), options, source);
}

Result<Reconstruction> reconstruct(const Mesh& scan, const align::Alignment& alignment,
                                   const ReconstructOptions& options, std::string_view source) {
  return reconstruct(canonical_scan(scan, alignment), options, source);
}

Result<Reconstruction> reconstruct(const CanonicalScan& scan, const ReconstructOptions& options,
                                   std::string_view source) {
  Result<slice::ProfileSet> profiles = extract_profiles(scan, options.profiles);
  if (!profiles) return with_source(std::move(profiles).error(), source);
  Result<pde::Surface> surface = surface_from(*profiles, options.pde, source);
  if (!surface) return with_source(std::move(surface).error(), source);

  Resolution grid = options.resolution.value_or(resolution_for(*profiles, options.grid_spacing_mm));
  if (grid.u == 0) grid = resolution_for(*profiles, grid.v);
  grid = {std::max<std::size_t>(grid.u, 2), std::max<std::size_t>(grid.v, 2)};
  Result<pdef::SurfaceMesh> meshes = pdef::surface_mesh(*surface, grid, scan.frame, source);
  if (!meshes) return std::move(meshes).error();
  const std::string name =
      scan.mesh.name.empty() ? std::string("pde surface") : scan.mesh.name + " (pde surface)";
  meshes->canonical.name = name;
  meshes->scan.name = name;
  return Reconstruction{std::move(profiles).value(), std::move(surface).value(), grid,
                        std::move(meshes->canonical), std::move(meshes->scan)};
}

} // namespace pdeface::pipeline

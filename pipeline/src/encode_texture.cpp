// The `.pdef` texture layer made from a scan: its colour where each texel's normal line meets it, over the
// PDE surface's (u, v) domain, holes filled smoothly, encoded as JPEG (docs/pdef-format.md, "The texture
// layer"; docs/pipeline.md).

#include "encode_texture.hpp"

#include "pdeface/core/parallel.hpp"
#include "pdeface/image/image.hpp"
#include "pdeface/metrics/colour.hpp"
#include "pdeface/pde/displacement.hpp"
#include "pdeface/residual/measure.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace pdeface::pipeline {
namespace {

// Texels whose normal line meets no scan within this (mm) take their neighbours' colour: as far as the
// residual layer looks, and a hole's rim within 2 mm is taken as the scan there.
constexpr residual::MeasureOptions kTexelLine{
    .max_offset_mm = 6.0, .tolerance_mm = 0.02, .rim_reach_mm = 2.0};
// The most texels a side (JPEG allows 65535; a face at 0.1 mm is 2000 × 2500).
constexpr std::size_t kMaxTexels = 4096;

} // namespace

Result<TexturedFace> make_texture(const Mesh& scan, const pde::Surface& surface,
                                  const TextureRequest& request, std::string_view source) {
  if (request.quality < 1 || request.quality > 100)
    throw std::invalid_argument("pipeline::make_texture: a quality of 1-100");
  Result<Texels> texels = sample_texels(scan, surface, request.texel_mm, source);
  if (!texels) return std::move(texels).error();
  return encode_texels(*texels, request.quality);
}

TexturedFace encode_texels(const Texels& texels, int quality) {
  TexturedFace out{Image{image::encode_jpeg(texels.pixels, {.quality = quality}), "image/jpeg", {}},
                   texels.outcome};
  out.outcome.bytes = out.texture.bytes.size();
  return out;
}

Result<Texels> sample_texels(const Mesh& scan, const pde::Surface& surface, double texel_mm,
                             std::string_view source) {
  if (!(texel_mm > 0) || !std::isfinite(texel_mm))
    throw std::invalid_argument("pipeline::sample_texels: a texel size above 0");
  Result<metrics::SurfaceColour> colour = metrics::SurfaceColour::of(scan, source);
  if (!colour) return std::move(colour).error();
  if (colour->source() == metrics::ColourSource::None)
    return make_error(ErrorCode::InvalidArgument,
                      "the scan has no colour for a texture layer: neither a photograph with texture "
                      "coordinates nor vertex colours",
                      std::string(source));
  const residual::GridSize size = residual::grid_for(surface, texel_mm);
  const std::size_t width = std::min(size.width, kMaxTexels), height = std::min(size.height, kMaxTexels);
  // Texel (x, y), y = 0 the top row, at the centre u = (x + ½) / W · u_max, v = π (1 − (y + ½) / H).
  std::vector<double> us(width), vs(height);
  for (std::size_t x = 0; x < width; ++x)
    us[x] = surface.u_max() * (static_cast<double>(x) + 0.5) / static_cast<double>(width);
  for (std::size_t y = 0; y < height; ++y)
    vs[y] = std::numbers::pi * (1.0 - (static_cast<double>(y) + 0.5) / static_cast<double>(height));
  const pde::NormalGrid grid = pde::normal_grid(surface, us, vs);
  const metrics::SurfaceDistance distance(scan);

  std::array<pde::Displacement, 3> channels;
  for (pde::Displacement& c : channels)
    c = {width, height, std::vector<double>(width * height, 0.0)};
  std::vector<std::uint8_t> found(width * height, 0);
  parallel_for(height, 0, [&](std::size_t y) {
    for (std::size_t x = 0; x < width; ++x) {
      const std::size_t p = y * width + x;
      const residual::Hit hit =
          residual::along_normal(distance, scan, grid.points[p], grid.normals[p], kTexelLine);
      if (!hit.found) continue;
      const std::optional<Eigen::Vector3f> c = colour->at(hit.point, hit.triangle);
      if (!c) continue;
      for (std::size_t k = 0; k < 3; ++k)
        channels[k].values[p] = (*c)(static_cast<Eigen::Index>(k));
      found[p] = 1;
    }
  });
  TextureOutcome outcome{width, height, 0.0, 0, colour->source()};
  outcome.found_share =
      static_cast<double>(std::count(found.begin(), found.end(), 1)) / static_cast<double>(found.size());
  if (outcome.found_share == 0)
    return make_error(ErrorCode::InvalidArgument, "no texel of the face met the scan: no texture layer",
                      std::string(source));
  for (pde::Displacement& c : channels) // holes and beyond the scan's edge: their surroundings' colour
    residual::fill(c, found);
  image::Pixels pixels{static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height),
                       std::vector<std::uint8_t>(width * height * 3)};
  for (std::size_t p = 0; p < width * height; ++p)
    for (std::size_t k = 0; k < 3; ++k)
      pixels.rgb[3 * p + k] =
          static_cast<std::uint8_t>(std::clamp(std::lround(255.0 * channels[k].values[p]), 0L, 255L));
  return Texels{std::move(pixels), outcome};
}

} // namespace pdeface::pipeline

#pragma once
// The texture layer's step inside the pipeline (encode.cpp, report.cpp): private to pipeline/.

#include "pdeface/image/image.hpp"
#include "pdeface/pipeline/encode.hpp"

#include <string_view>

namespace pdeface::pipeline {

//! A texture layer and what it took.
struct TexturedFace {
  Image texture; //!< the JPEG image
  TextureOutcome outcome;
};

//! The texels of a texture layer before they are encoded: the scan's colours over the surface.
struct Texels {
  image::Pixels pixels;
  TextureOutcome outcome; //!< `bytes` 0 until encoded
};

//! `make_texture`'s first step, the texels at `texel_mm` (what every quality of a texture layer shares).
[[nodiscard]] Result<Texels> sample_texels(const Mesh& scan, const pde::Surface& surface, double texel_mm,
                                           std::string_view source);
//! Its second: the texels as a JPEG image of `quality`.
[[nodiscard]] TexturedFace encode_texels(const Texels& texels, int quality);

//! The texture layer of `surface` (canonical frame, mm) from `scan` (the same frame): each texel the scan's
//! colour (its photograph through its texture coordinates, else its vertex colours) where the texel's
//! normal line meets it, texels that meet none filled from their neighbours, as a JPEG image of
//! `request.quality`. Errors: `InvalidArgument` for a scan without colour or one the surface's normals
//! never meet; those of decoding the scan's photograph. \throw std::invalid_argument for a texel size that
//! is not positive or a quality outside 1-100
[[nodiscard]] Result<TexturedFace> make_texture(const Mesh& scan, const pde::Surface& surface,
                                                const TextureRequest& request, std::string_view source);

} // namespace pdeface::pipeline

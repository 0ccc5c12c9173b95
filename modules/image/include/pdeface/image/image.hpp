#pragma once
//! \file
//! Images as pixels: a face's photograph decoded (JPEG through libjpeg-turbo, PNG through stb_image),
//! sampled where a texture coordinate points, resized, and encoded as JPEG (the `.pdef` texture layer,
//! docs/pdef-format.md). Colours are 8-bit sRGB, as the files hold them.

#include "pdeface/core/image.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace pdeface::image {

//! An RGB image, rows top to bottom, 3 bytes a pixel (sRGB).
struct Pixels {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<std::uint8_t> rgb;

  [[nodiscard]] bool empty() const { return rgb.empty(); }
  //! Pixel (x, y), y = 0 the top row, as three values in [0, 1].
  [[nodiscard]] Eigen::Vector3f at(std::uint32_t x, std::uint32_t y) const;
};

//! Decodes a JPEG or PNG image, its header checked first (`inspect_image`: at most `max_pixels`). Errors,
//! naming `source`: those of `inspect_image`, and `Malformed` for data the decoder refuses (a corrupt or
//! truncated image).
[[nodiscard]] Result<Pixels> decode(std::string_view bytes, std::string_view source,
                                    std::uint64_t max_pixels = kMaxImagePixels);

//! Decodes a material's image (its bytes), as `decode`.
[[nodiscard]] Result<Pixels> decode(const Image& image, std::string_view source);

struct JpegOptions {
  int quality = 85;      //!< 1-100, libjpeg's scale
  bool subsample = true; //!< chroma at half resolution each way (4:2:0), else 4:4:4
};

//! The image as a baseline JPEG. \throw std::invalid_argument for an empty image or a quality outside
//! 1-100
[[nodiscard]] std::string encode_jpeg(const Pixels& pixels, const JpegOptions& options = {});

//! The colour at texture coordinate `st` (OBJ's convention: (0, 0) the image's bottom left, (1, 1) its top
//! right; clamped to the image), bilinear between pixel centres, each channel in [0, 1].
//! \throw std::invalid_argument for an empty image
[[nodiscard]] Eigen::Vector3f sample(const Pixels& pixels, const Vec2f& st);

//! The image at `width` × `height` (each at least 1): every pixel the mean of the source area it covers.
//! \throw std::invalid_argument for an empty image or a zero size
[[nodiscard]] Pixels resized(const Pixels& pixels, std::uint32_t width, std::uint32_t height);

//! sRGB's transfer function and its inverse (IEC 61966-2-1), for colours in [0, 1]: a mesh's vertex
//! colours are linear, an image's pixels sRGB.
[[nodiscard]] float to_srgb(float linear);
[[nodiscard]] float to_linear(float srgb);

} // namespace pdeface::image

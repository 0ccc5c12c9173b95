#pragma once
//! \file
//! The images a mesh's material refers to, checked without decoding them, and the files a mesh file refers
//! to (OBJ's `mtllib` and `map_Kd`, a glTF image's `uri`, a VRML `ImageTexture` url), obtained through a
//! resolver that the caller supplies (readers parse bytes in memory and never open a file themselves).

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

namespace pdeface {

//! The most pixels an image may declare: 8192 × 8192 (64 Mpx, 256 MiB as decoded RGBA), far above a face
//! photo (james.jpg: 2400 × 1600) and a bound on what a "decompression bomb" (a few bytes declaring
//! gigapixels) can make a viewer allocate.
inline constexpr std::uint64_t kMaxImagePixels = std::uint64_t{1} << 26;

//! What an image's header says.
struct ImageInfo {
  std::string_view mime_type; //!< "image/jpeg" or "image/png"
  std::uint32_t width = 0;
  std::uint32_t height = 0;
};

//! The MIME type the first bytes identify ("image/jpeg", "image/png"), if either.
[[nodiscard]] std::optional<std::string_view> image_mime_type(std::string_view bytes) noexcept;
//! ".jpg" for "image/jpeg", ".png" for "image/png", ".bin" for anything else.
[[nodiscard]] std::string_view image_extension(std::string_view mime_type) noexcept;

//! Reads a JPEG's or PNG's header (nothing is decoded): the JPEG markers up to its frame header, the PNG
//! signature and IHDR chunk. Errors, at the byte of the image where found and naming `source`:
//! `UnsupportedFormat` (neither JPEG nor PNG), `Truncated`, `Malformed` (a marker or chunk out of place, a
//! zero dimension), `CountTooLarge` (more than `max_pixels`).
[[nodiscard]] Result<ImageInfo> inspect_image(std::string_view bytes, std::string_view source,
                                              std::uint64_t max_pixels = kMaxImagePixels);

//! The bytes of a file that another file refers to by `reference`, as written in it (a relative path, a
//! URI). An error (`Io` for a missing or unreadable file, `UnsupportedFormat` for a reference that may not
//! be followed, `CountTooLarge`) is a note to the reader, never a failure: the reference is dropped.
using Resolver = std::function<Result<std::string>(std::string_view reference)>;

//! The image `reference` names, through `resolve`: its bytes and MIME type, checked by `inspect_image`.
//! When the resolver is empty or fails, or the image is neither JPEG nor PNG, a note says so and the image
//! has no bytes (only its `uri`). `source` names the file holding the reference, for notes.
//! Errors: those of `inspect_image` (a corrupt image, or one of more than `kMaxImagePixels`), naming the
//! image file.
[[nodiscard]] Result<Image> resolve_image(const Resolver& resolve, std::string_view reference,
                                          std::string_view source, Notes* notes);

} // namespace pdeface

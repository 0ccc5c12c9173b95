#pragma once
//! \file
//! The `.pdef` document: a face as its profile curves, what rebuilds the PDE surface through them and the
//! similarity back to the scan's frame, encoded to bytes and decoded from them (docs/pdef-format.md is the
//! normative specification). No file I/O: `pdeface::formats` reads and writes files.
//!
//! Decoding untrusted bytes is safe: every length and count is checked against the bytes that remain
//! before anything is allocated, the whole file against its checksum before its contents are read, and
//! every problem is an `Error` with a code and the byte offset where it was found.

#include "pdeface/core/image.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"
#include "pdeface/core/similarity.hpp"
#include "pdeface/pde/surface.hpp"
#include "pdeface/pdef/residual.hpp"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace pdeface::pdef {

//! The similarity from the scan's frame to the canonical face frame, p_canonical = scale · R · p_scan + t,
//! and the scan's units: core's `FaceFrame`, the type alignment finds (`align::FaceFrame`).
using Frame = FaceFrame;

//! A named point of the face (canonical frame, mm), e.g. "nose_tip".
struct Landmark {
  std::string name;
  Vec3 position = Vec3::Zero();
};

//! How a decoded document's numbers were stored (set by `decode`; `encode` reuses a lossy grid when its
//! options allow, so that encode → decode → encode gives the same bytes).
struct Storage {
  bool lossless = true;
  double step_mm = 0.0;       //!< lossy: the grid of the samples' y and z (mm)
  double plane_step_mm = 0.0; //!< lossy: the grid of the curves' planes x (mm)
  bool frame_float64 = true;  //!< the frame's numbers as float64 (else float32)
  //! lossy: y stored as heights with an anchor every `heights_stride` curves on a grid of 2^-`heights_bits`
  //! (0: y predicted sample by sample)
  std::uint32_t heights_stride = 0;
  std::uint32_t heights_bits = 0;
};

//! A face as `.pdef` holds it: J curves of K samples in the canonical frame (mm), curve j in the plane
//! x = planes[j], ascending, each sample chin to forehead (v = 0 at the chin); the curve's extent is the
//! height of its first and last sample.
struct Face {
  pde::Curves curves;         //!< curves.samples[j]: K × 3 (x, y, z); units mm
  std::vector<double> planes; //!< x_j of every curve (mm), ascending
  std::vector<std::vector<bool>>
      filled;  //!< filled[j][k]: sample k of curve j lies in a hole the slicer filled
  Frame frame; //!< back to the scan
  //! The PDE options the surface is built with, as used: `smoothing` and `modes` are always set, so that a
  //! decoder never recomputes them from (quantised) data.
  pde::Options pde;
  std::vector<Landmark> landmarks; //!< optional
  std::string name;                //!< optional (UTF-8)
  Storage storage;                 //!< how `decode` found it stored
  //! A version 3 file's residual layer as decoded (`encode` writes curves only: `with_residual` adds one).
  std::optional<Residual> residual;
  //! The texture layer: the face's photograph over the surface's (u, v) domain, a JPEG image (the bytes
  //! as stored, never decoded here; docs/pdef-format.md, "The texture layer"). Pixel column x's centre is
  //! at u = (x + ½) / W · u_max and row y's (0 the top) at v = π · (1 − (y + ½) / H): the surface point
  //! (u, v) takes texture coordinate (u / u_max, v / π), (0, 0) the image's bottom left.
  std::optional<Image> texture;

  [[nodiscard]] std::size_t curve_count() const { return curves.samples.size(); }
  [[nodiscard]] std::size_t sample_count() const {
    return curves.samples.empty() ? 0 : static_cast<std::size_t>(curves.samples.front().rows());
  }
  //! Curve j's [bottom, top]: the heights of its first and last samples (mm).
  [[nodiscard]] std::array<double, 2> extent(std::size_t j) const;
};

//! The largest documents a file may describe (docs/pdef-format.md, "Limits").
inline constexpr std::size_t kMinCurves = 4;
inline constexpr std::size_t kMaxCurves = 1024;
inline constexpr std::size_t kMaxSamples = pde::max_samples;
//! J·K may not exceed kFreeSamples + kSamplesPerByte × the file's length: what a file of a given size may
//! make a decoder allocate is bounded (~40 bytes per sample).
inline constexpr std::size_t kFreeSamples = 4096;
inline constexpr std::size_t kSamplesPerByte = 256;
inline constexpr std::size_t kMaxLandmarks = 256;
inline constexpr std::size_t kMaxLandmarkName = 64;
inline constexpr std::size_t kMaxName = 1024;
inline constexpr std::size_t kMaxFileBytes = std::size_t{1} << 26;

//! The default maximum error of a lossy file (mm).
inline constexpr double kDefaultMaxError = 0.05;

struct EncodeOptions {
  //! Exact: every double of the curves, planes, frame and landmarks as it is (float64, compressed).
  bool lossless = false;
  //! Lossy: every sample within this distance (mm) of its original, and the surface decoded from the file
  //! within this distance of the surface through the original curves (checked by the encoder).
  double max_error_mm = kDefaultMaxError;
};

//! What `encode` made, with what it measured.
struct Encoded {
  std::string bytes;
  double step_mm = 0.0;          //!< lossy: the samples' grid (mm)
  double max_sample_error = 0.0; //!< lossy: the largest distance of a decoded sample from its original (mm)
  double max_surface_error =
      0.0; //!< lossy: the largest distance of the decoded surface from the original (mm)
  std::size_t tightenings =
      0; //!< lossy: how often the grid was made finer to keep the surface within the error
};

//! Encodes a face. Errors: `InvalidArgument` for a face that breaks the document's rules (curve and sample
//! counts, planes not ascending, sizes that do not match, names too long, limits above, a maximum error that
//! is not positive, a texture that is not one JPEG image) or a surface that cannot be built from it;
//! `NonFinite` for a NaN or infinite number.
[[nodiscard]] Result<Encoded> encode(const Face& face, const EncodeOptions& options = {});

//! A version 2 file that `encode` wrote, with `texture` added as its texture layer: the same bytes as
//! encoding the face with it (the layer is the last section). Errors: `InvalidArgument` for a texture that
//! is not one JPEG image, a file that is not a valid version 2 file or has a texture layer already.
[[nodiscard]] Result<std::string> with_texture(std::string_view file, const Image& texture);

//! What a decoder reads of a file.
struct DecodeOptions {
  //! The texture layer's image bytes (its header checked); false: the section is skipped unread, as a
  //! reader of shape alone does.
  bool texture = true;
};

//! Decodes a `.pdef` document. Errors (each with the byte offset): `Empty`, `BadMagic` (byte 0),
//! `UnsupportedVersion` (byte 4), `UnsupportedFormat` (unknown required flags or sections), `Truncated`,
//! `Malformed` (trailing bytes, bad field values, sections out of order), `ChecksumMismatch`,
//! `CountTooLarge` (counts beyond the limits or beyond what the file's size can hold), `NonFinite`.
//! A texture layer that is not one JPEG image within `kMaxImagePixels` is `Malformed` (or the image's own
//! error) at its byte.
[[nodiscard]] Result<Face> decode(std::string_view bytes, std::string_view source = {},
                                  const DecodeOptions& options = {});

//! One part of a file, for `pdeface info`.
struct Section {
  //! "header", "face", "curves", "landmarks", "name", "texture", "checksum" or "ancillary 0x.."
  std::string name;
  std::size_t offset = 0;
  std::size_t bytes = 0;
};

//! The parts of a file and their sizes (the container checked: header, lengths, checksum). Errors: those
//! of `decode` about the container.
[[nodiscard]] Result<std::vector<Section>> sections(std::string_view bytes, std::string_view source = {});

//! The CRC-32 (ISO-HDLC, as zlib's `crc32`) the format uses; for tests that make hostile files.
[[nodiscard]] std::uint32_t checksum(std::string_view bytes);

//! The magic bytes a `.pdef` file starts with.
inline constexpr std::string_view kMagic{"PDEF"};

} // namespace pdeface::pdef

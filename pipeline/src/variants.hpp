#pragma once
// The encodings `compare_scan` measures, each giving its bytes, the mesh its bytes decode to and the time
// both took. Internal to the pipeline: the report is the API.

#include "pdeface/align/detect.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface/pipeline/encode.hpp"
#include "pdeface/pipeline/reconstruct.hpp"
#include "pdeface/pipeline/report.hpp"

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

namespace pdeface::pipeline::detail {

using Clock = std::chrono::steady_clock;
[[nodiscard]] inline double milliseconds_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

//! An encoding and what decoding its bytes gave back (in the scan's frame and units).
struct Encoded {
  std::string bytes;
  Mesh decoded;
  double encode_ms = 0.0;
  double decode_ms = 0.0;
  int bits = 0;                    //!< Draco: the position quantisation used
  std::size_t beside_bytes = 0;    //!< what goes beside the file (a photograph the mesh's UVs map into)
  std::size_t image_bytes = 0;     //!< of the bytes, an image's (beside the file or inside it)
  std::size_t attribute_bytes = 0; //!< of the file, its colour attributes' (texture coordinates, colours)
};

//! gzip (RFC 1952) through zlib, and back. Errors: `Malformed` for bytes that are not gzip.
[[nodiscard]] std::string gzip(std::string_view bytes, int level);
[[nodiscard]] Result<std::string> gunzip(std::string_view bytes);

//! The mesh as a raw file of `format` (float32 positions, triangles), optionally gzipped.
[[nodiscard]] Result<Encoded> encode_raw(const Mesh& geometry, formats::Format format, bool gzipped,
                                         int gzip_level);

//! The mesh through our Draco writer at `bits` (positions) and `level`; with its texture coordinates and
//! colours when it has them, at `uv_bits` and `color_bits`.
[[nodiscard]] Result<Encoded> encode_draco(const Mesh& geometry, int bits, int level, int uv_bits = 12,
                                           int color_bits = 8);

//! The mesh simplified by meshoptimizer to `target` triangles (the most it can reach: fewer triangles
//! than the scan has), vertices on no triangle dropped.
[[nodiscard]] Mesh simplify(const Mesh& geometry, std::size_t target, bool lock_border);

//! Decimate + Draco within `budget` bytes: for each of `options.decimate_bits`, a triangle count whose
//! Draco bytes fit in [budget × (1 − slack), budget] (found by secant steps on log bytes against log
//! triangles, each a simplification and an encoding; the first at the next bits predicted from the last
//! fitting mesh encoded at those bits); of those, the one `error` (of the decoded mesh, in the scan's
//! frame) finds best, from the fewest bits up until it has grown twice in a row. `whole_bytes`: the whole
//! `geometry`'s Draco bytes at some bits, when known (the Draco rows): bits at which it is under the budget's
//! range are skipped, and the others start from it. Errors: `InvalidArgument` for a point cloud or a
//! budget too small for any mesh.
struct Decimated {
  Encoded encoded;
  int bits = 0;
  std::size_t tried = 0; //!< encodings made in the search
};
[[nodiscard]] Result<Decimated> decimate_to_budget(const Mesh& geometry, std::size_t budget,
                                                   const CompareOptions& options,
                                                   const std::function<double(const Mesh&)>& error,
                                                   const std::map<int, std::size_t>& whole_bytes = {});

//! The `.pdef` files of one aligned scan, and what a reader makes of their bytes. `make(ratio, lossless,
//! size)` is the file `encode_aligned` writes of the scan sliced at `ratio` (lossy within the default error,
//! or lossless; `scheme`; with `size`, a residual layer after the curves, the file at most `size` bytes:
//! `pdeface encode --size`; with `texture`, a texture layer: `pdeface encode --texture`), byte for byte,
//! decoded by `pdef::decode` and meshed in the scan's frame at the default grid (`pdef::to_mesh`), encoding
//! and decoding timed apart. What the files share is made once: the slicing and the surface at each ratio
//! (for its lossy and lossless files), the lossy file under the files with a residual layer, and each
//! residual grid (one for every size it serves); a file's `encode_ms` counts every step it took, shared or
//! not, as if it had been made alone. Thread-safe; `alignment` and `canonical` (the scan in the
//! canonical frame, `canonical_scan`) must outlive it.
class PdeFiles {
public:
  PdeFiles(const align::Alignment& alignment, const CanonicalScan& canonical, pde::Scheme scheme,
           std::string source);
  PdeFiles(const PdeFiles&) = delete;
  PdeFiles& operator=(const PdeFiles&) = delete;
  ~PdeFiles();

  [[nodiscard]] Result<Encoded> make(double ratio, bool lossless,
                                     std::optional<std::size_t> size = std::nullopt,
                                     const TextureRequest& texture = {});

private:
  struct AtRatio;
  [[nodiscard]] EncodeRequest request(double ratio, bool lossless, std::optional<std::size_t> size,
                                      const TextureRequest& texture = {}) const;
  AtRatio& at(double ratio);

  const align::Alignment& alignment_;
  const CanonicalScan& canonical_;
  pde::Scheme scheme_;
  std::string source_;
  std::mutex mutex_; // guards `ratios_`'s insertions
  std::map<double, std::unique_ptr<AtRatio>> ratios_;
};

} // namespace pdeface::pipeline::detail

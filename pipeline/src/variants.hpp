#pragma once
// The encodings `compare_scan` measures, each giving its bytes, the mesh its bytes decode to and the time
// both took. Internal to the pipeline: the report is the API.

#include "pdeface/align/detect.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface/pipeline/report.hpp"

#include <chrono>
#include <functional>
#include <map>
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
  int bits = 0; //!< Draco: the position quantisation used
};

//! gzip (RFC 1952) through zlib, and back. Errors: `Malformed` for bytes that are not gzip.
[[nodiscard]] std::string gzip(std::string_view bytes, int level);
[[nodiscard]] Result<std::string> gunzip(std::string_view bytes);

//! The mesh as a raw file of `format` (float32 positions, triangles), optionally gzipped.
[[nodiscard]] Result<Encoded> encode_raw(const Mesh& geometry, formats::Format format, bool gzipped,
                                         int gzip_level);

//! The mesh through our Draco writer at `bits` (positions) and `level`.
[[nodiscard]] Result<Encoded> encode_draco(const Mesh& geometry, int bits, int level);

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

//! The `.pdef` file of the aligned scan sliced at `ratio` (`encode_aligned`: lossy within the default error,
//! or lossless; `scheme`), and what a reader makes of its bytes: `pdef::decode`, then the surface solved and
//! meshed in the scan's frame at the default grid (`pdef::to_mesh`). Encoding and decoding timed apart.
//! With `size`: a residual layer after the curves, the file at most `size` bytes (`pdeface encode --size`).
[[nodiscard]] Result<Encoded> encode_pde(const Mesh& scan, const align::Alignment& alignment, double ratio,
                                         bool lossless, pde::Scheme scheme, std::string_view source,
                                         std::optional<std::size_t> size = std::nullopt);

} // namespace pdeface::pipeline::detail

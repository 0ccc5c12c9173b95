// STL read by our validator, written through OpenMesh. OpenMesh's STL reader cannot tell binary from ASCII in
// a stream, crashes on a lying facet count, accepts a cut-off file, reads words and "nan" without complaint
// (third_party_notes/openmesh.md), and merges corners up to FLT_MIN apart through a comparison that is not
// an ordering (its set_epsilon changes nothing): corners 5e-39 apart written by its own writer came back
// merged into degenerate facets (found by fuzzing). The validator reads every corner anyway, so it builds
// the mesh: equal corners merged into shared vertices, exactly.

#include "pdeface/stl/stl.hpp"

#include "pdeface/core/bytes.hpp"
#include "pdeface/core/text.hpp"
#include "pdeface/openmesh_io/openmesh_io.hpp"
#include "pdeface/text/scanner.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

namespace pdeface::stl {
namespace {

using text::Scanner;
using text::Token;

constexpr std::size_t kHeaderBytes = 80;
constexpr std::size_t kPreambleBytes = 84; // header + facet count
constexpr std::size_t kFacetBytes = 50;    // normal, 3 corners (12 floats), 2 attribute bytes

std::uint32_t load_u32(std::string_view bytes, std::size_t offset) {
  return load_le<std::uint32_t>(bytes, offset);
}

float load_float(std::string_view bytes, std::size_t offset) { return load_le_f32(bytes.data() + offset); }

// "units mm" anywhere in free text (the binary header, the solid line), as our writer puts it.
Units units_in(std::string_view text) {
  Scanner scan(text);
  for (Token t = scan.next(); !t.empty(); t = scan.next())
    if (t.text == "units")
      if (const std::optional<Units> units = units_from_string(scan.next().text)) return *units;
  return Units::Unknown;
}

// A file is binary when its size matches its facet count, even if its header starts with "solid" (some
// exporters write that); otherwise it is ASCII if it starts with "solid".
bool is_binary(std::string_view bytes) {
  if (bytes.size() >= kPreambleBytes &&
      kPreambleBytes + std::uint64_t{load_u32(bytes, kHeaderBytes)} * kFacetBytes == bytes.size())
    return true;
  return !Scanner(bytes).next().text.starts_with("solid");
}

// Facets to a mesh: equal corners (as float32; -0 equals 0) become one vertex, numbered in the order corners
// first appear; a facet two of whose corners are the same point is skipped, and counted.
class FacetSoup {
public:
  void add(const std::array<float, 9>& corners) {
    std::array<std::uint32_t, 3> v{};
    for (std::size_t k = 0; k < 3; ++k)
      v[k] = vertex({corners[3 * k] + 0.0F, corners[3 * k + 1] + 0.0F, corners[3 * k + 2] + 0.0F});
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2])
      ++skipped;
    else
      mesh.triangles.push_back({v[0], v[1], v[2]});
  }

  Mesh mesh;
  std::size_t skipped = 0;

private:
  std::uint32_t vertex(const std::array<float, 3>& p) {
    const auto [it, fresh] = index_.try_emplace(p, static_cast<std::uint32_t>(mesh.positions.size()));
    if (fresh) mesh.positions.emplace_back(p[0], p[1], p[2]);
    return it->second;
  }
  std::map<std::array<float, 3>, std::uint32_t> index_; // finite values only: an ordering
};

struct Checked {
  Units units = Units::Unknown;
  FacetSoup soup;
};

Result<Checked> check_binary(std::string_view bytes, std::string_view source, Notes* notes) {
  auto fail = [&](ErrorCode code, std::size_t byte, std::string message) {
    return make_error(code, std::move(message), std::string(source), Location::at_byte(byte));
  };
  if (bytes.size() < kPreambleBytes)
    return fail(
        ErrorCode::Truncated, bytes.size(),
        fmt::format("the file has {} bytes; a binary STL starts with an 80-byte header and a 4-byte facet "
                    "count",
                    bytes.size()));
  const std::uint64_t facets = load_u32(bytes, kHeaderBytes);
  if (facets == 0) return make_error(ErrorCode::Empty, "the STL file has no facets", std::string(source));
  if (facets * kFacetBytes > bytes.size())
    return fail(ErrorCode::CountTooLarge, kHeaderBytes,
                fmt::format("{} facets of 50 bytes declared ({} bytes), but the whole file has {} bytes",
                            facets, facets * kFacetBytes, bytes.size()));
  const std::uint64_t end = kPreambleBytes + facets * kFacetBytes;
  if (end > bytes.size()) {
    const std::uint64_t whole = (bytes.size() - kPreambleBytes) / kFacetBytes;
    return fail(ErrorCode::Truncated, kPreambleBytes + whole * kFacetBytes,
                fmt::format("the file ends at byte {} inside facet {} of {}, which starts here", bytes.size(),
                            whole, facets));
  }
  Checked checked{units_in(bytes.substr(0, kHeaderBytes)), {}};
  for (std::uint64_t f = 0; f < facets; ++f) {
    std::array<float, 9> corners{};
    for (std::size_t k = 0; k < corners.size(); ++k) { // after the facet's normal (3 floats)
      const std::size_t at = kPreambleBytes + f * kFacetBytes + 12 + 4 * k;
      corners[k] = load_float(bytes, at);
      if (!std::isfinite(corners[k]))
        return fail(ErrorCode::NonFinite, at, fmt::format("facet {} has a non-finite corner coordinate", f));
    }
    checked.soup.add(corners);
  }
  if (notes && end < bytes.size())
    notes->push_back(fmt::format("{}: {} bytes after the last facet ignored (from byte {})", source,
                                 bytes.size() - end, end));
  return checked;
}

class AsciiChecker {
public:
  AsciiChecker(std::string_view bytes, std::string_view source)
      : bytes_(bytes), scan_(bytes), source_(source) {}

  // solid [name]  (facet normal n n n  outer loop  (vertex x y z){3}  endloop  endfacet)*  endsolid [name]
  Result<Checked> run() {
    scan_.next(); // "solid", checked by is_binary
    Checked checked{units_in(bytes_.substr(0, bytes_.find('\n'))), {}};
    scan_.skip_line();
    std::uint64_t facets = 0;
    for (Token t = scan_.next(); t.text != "endsolid"; t = scan_.next(), ++facets) {
      if (t.empty()) return fail(ErrorCode::Truncated, scan_.here(), "the file ends without endsolid");
      if (t.text != "facet") return unexpected(t, "facet or endsolid");
      if (Result<void> ok = facet(checked.soup); !ok) return std::move(ok).error();
    }
    if (facets == 0) return make_error(ErrorCode::Empty, "the STL file has no facets", std::string(source_));
    return checked;
  }

private:
  Error fail(ErrorCode code, Location where, std::string message) const {
    return make_error(code, std::move(message), std::string(source_), where);
  }
  Error unexpected(const Token& t, std::string_view expected) const {
    if (t.empty())
      return fail(ErrorCode::Truncated, scan_.here(),
                  fmt::format("the file ends where {} was expected", expected));
    return fail(ErrorCode::Malformed, t.location(),
                fmt::format("expected {}, found '{}'", expected, excerpt(t.text)));
  }
  Result<void> keyword(std::string_view word) {
    const Token t = scan_.next();
    if (t.text == word) return {};
    return unexpected(t, fmt::format("'{}'", word));
  }
  // Three numbers into `out` (as float32), finite ones if `finite`.
  Result<void> numbers(std::string_view what, bool finite, float* out) {
    for (int k = 0; k < 3; ++k) {
      const Token t = scan_.next();
      if (t.empty()) return unexpected(t, what);
      const std::optional<float> v = text::parse_real<float>(t.text);
      if (!v) return unexpected(t, what);
      if (finite && !std::isfinite(*v))
        return fail(ErrorCode::NonFinite, t.location(),
                    fmt::format("{} is {}, not a finite float", what, excerpt(t.text)));
      out[k] = *v;
    }
    return {};
  }
  Result<void> facet(FacetSoup& soup) {
    std::array<float, 3> normal{};
    std::array<float, 9> corners{};
    if (Result<void> ok = keyword("normal"); !ok) return ok;
    if (Result<void> ok = numbers("a normal component", false, normal.data()); !ok) return ok;
    if (Result<void> ok = keyword("outer"); !ok) return ok;
    if (Result<void> ok = keyword("loop"); !ok) return ok;
    for (std::size_t corner = 0; corner < 3; ++corner) {
      if (Result<void> ok = keyword("vertex"); !ok) return ok;
      if (Result<void> ok = numbers("a corner coordinate", true, &corners[3 * corner]); !ok) return ok;
    }
    if (Result<void> ok = keyword("endloop"); !ok) return ok;
    if (Result<void> ok = keyword("endfacet"); !ok) return ok;
    soup.add(corners);
    return {};
  }

  std::string_view bytes_;
  Scanner scan_;
  std::string_view source_;
};

} // namespace

Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes) {
  if (bytes.empty()) return make_error(ErrorCode::Empty, "the file is empty", std::string(source));
  const bool binary = is_binary(bytes);
  Result<Checked> checked = binary ? check_binary(bytes, source, notes) : AsciiChecker(bytes, source).run();
  if (!checked) return std::move(checked).error();
  Mesh mesh = std::move(checked->soup.mesh);
  mesh.units = checked->units;
  if (notes && checked->soup.skipped > 0)
    notes->push_back(fmt::format("{}: {} degenerate facets skipped (two corners at the same point)", source,
                                 checked->soup.skipped));
  if (Result<void> valid = validate(mesh, source); !valid) return std::move(valid).error();
  return mesh;
}

Result<std::string> write(const Mesh& mesh, const WriteOptions& options, Notes* notes) {
  if (Result<void> valid = check_writable(mesh); !valid) return std::move(valid).error();
  if (mesh.is_point_cloud())
    return make_error(ErrorCode::InvalidArgument,
                      "STL cannot hold a point cloud (the mesh has no triangles)");
  Result<std::string> bytes =
      openmesh_io::write_openmesh(mesh, {.extension = "stl", .binary = options.binary}, "STL", notes);
  if (!bytes) return bytes;
  // The binary header and the solid line are free text: they name the writer and state the units.
  const std::string units =
      mesh.units == Units::Unknown ? "" : fmt::format(" units {}", to_string(mesh.units));
  if (options.binary) {
    std::string header = fmt::format("binary STL written by pdeface{}", units);
    header.resize(kHeaderBytes, ' ');
    bytes->replace(0, kHeaderBytes, header);
  } else {
    bytes->replace(0, bytes->find('\n'), fmt::format("solid pdeface{}", units));
  }
  return bytes;
}

} // namespace pdeface::stl

#include "pdeface/formats/formats.hpp"

#include "pdeface/core/file.hpp"
#include "pdeface/core/text.hpp"
#include "pdeface/draco/draco.hpp"
#include "pdeface/gltf/gltf.hpp"
#include "pdeface/obj/obj.hpp"
#include "pdeface/off/off.hpp"
#include "pdeface/pdef/mesh.hpp"
#include "pdeface/pdef/pdef.hpp"
#include "pdeface/ply/binary.hpp"
#include "pdeface/ply/ply.hpp"
#include "pdeface/stl/stl.hpp"
#include "pdeface/vrml/vrml.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cstdint>
#include <string>

namespace pdeface::formats {
namespace {

constexpr std::array<std::string_view, 2> kVrmlExt{".wrl", ".vrml"};
constexpr std::array<std::string_view, 1> kObjExt{".obj"};
constexpr std::array<std::string_view, 1> kPlyExt{".ply"};
constexpr std::array<std::string_view, 1> kOffExt{".off"};
constexpr std::array<std::string_view, 1> kStlExt{".stl"};
constexpr std::array<std::string_view, 1> kGltfExt{".gltf"};
constexpr std::array<std::string_view, 1> kGlbExt{".glb"};
constexpr std::array<std::string_view, 1> kDracoExt{".drc"};
constexpr std::array<std::string_view, 1> kPdefExt{".pdef"};

// name, extensions, faces, point clouds, normals, colours, texcoords, lossy, writable, materials
constexpr std::array<FormatInfo, 9> kFormats{{
    {Format::Vrml, "VRML", kVrmlExt, true, true, true, true, true, false, true, true},
    {Format::Obj, "OBJ", kObjExt, true, true, true, true, true, false, true, true},
    {Format::Ply, "PLY", kPlyExt, true, true, true, true, true, false, true, true},
    {Format::Off, "OFF", kOffExt, true, true, false, true, false, false, true, false},
    {Format::Stl, "STL", kStlExt, true, false, false, false, false, false, true, false},
    {Format::Gltf, "glTF", kGltfExt, true, true, true, true, true, false, true, true},
    {Format::Glb, "GLB", kGlbExt, true, true, true, true, true, false, true, true},
    {Format::Draco, "Draco", kDracoExt, true, true, true, true, true, true, true, false},
    {Format::Pdef, "PDEF", kPdefExt, true, false, true, false, false, true, false, false},
}};

std::string lowercase(std::string s) {
  std::ranges::transform(s, s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// ".wrl .obj .ply ...": every format's canonical extension, for messages.
std::string extension_list() {
  std::string out;
  for (const FormatInfo& f : kFormats)
    out += (out.empty() ? "" : " ") + std::string(f.extensions.front());
  return out;
}

bool starts_with_ci(std::string_view bytes, std::string_view prefix) {
  if (bytes.size() < prefix.size()) return false;
  return lowercase(std::string(bytes.substr(0, prefix.size()))) == prefix;
}

std::string_view skip_space(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front())))
    s.remove_prefix(1);
  return s;
}

// A `.pdef` file read as a mesh: its surface in the scan's frame and units.
Result<Mesh> read_pdef(std::string_view bytes, std::string_view source, const ReadOptions& options) {
  if (options.pdef_max_bytes != 0) bytes = bytes.substr(0, options.pdef_max_bytes);
  Result<pdef::Face> face = pdef::decode(bytes, source);
  if (!face) return std::move(face).error();
  std::optional<pdef::Resolution> grid;
  if (options.surface_u != 0 || options.surface_v != 0)
    grid = pdef::Resolution{options.surface_u, options.surface_v};
  return pdef::to_mesh(*face, grid, source);
}

Result<Mesh> decode(Format format, std::string_view bytes, std::string_view source,
                    const ReadOptions& options, Notes* notes) {
  // References are followed through the caller's resolver, or noted and left.
  const Resolver none = [](std::string_view) -> Result<std::string> {
    return make_error(ErrorCode::UnsupportedFormat, "files it refers to are not read (--no-companions)");
  };
  const Resolver& resolve = options.companions ? options.resolver : none;
  switch (format) {
  case Format::Vrml: return vrml::read(bytes, source, notes, resolve);
  case Format::Obj: return obj::read(bytes, source, notes, resolve);
  case Format::Ply: return ply::read(bytes, source, notes, resolve);
  case Format::Off: return off::read(bytes, source, notes);
  case Format::Stl: return stl::read(bytes, source, notes);
  case Format::Gltf:
  case Format::Glb: return gltf::read(bytes, source, notes, resolve);
  case Format::Draco: return drc::read(bytes, source, notes);
  case Format::Pdef: return read_pdef(bytes, source, options);
  }
  return make_error(ErrorCode::UnsupportedFormat, "unknown format", std::string(source));
}

// `mesh` as the target format can hold it: itself when the format holds all of it (no copy: at a million
// vertices a copy is 60 MB), else a copy in `storage` without what it cannot hold, with a note for each
// attribute lost.
const Mesh& fit_to(const FormatInfo& fi, const Mesh& mesh, std::optional<Mesh>& storage, Notes* notes) {
  const bool drop_normals = mesh.has_normals() && !fi.normals, drop_colors = mesh.has_colors() && !fi.colors,
             drop_texcoords = mesh.has_texcoords() && !fi.texcoords,
             drop_material = mesh.material && !fi.materials;
  const bool stray_corners = !mesh.has_texcoords() && !mesh.texcoord_triangles.empty();
  if (!drop_normals && !drop_colors && !drop_texcoords && !drop_material && !stray_corners) return mesh;
  Mesh& out = storage.emplace(mesh);
  auto drop = [&](auto& attribute, bool dropped, std::string_view what) {
    if (!dropped) return;
    attribute.clear();
    if (notes) notes->push_back(fmt::format("{} dropped: {} cannot store them", what, fi.name));
  };
  drop(out.normals, drop_normals, "normals");
  drop(out.colors, drop_colors, "vertex colours");
  drop(out.texcoords, drop_texcoords, "texture coordinates");
  if (out.texcoords.empty()) out.texcoord_triangles.clear();
  if (drop_material) {
    out.material.reset();
    if (notes)
      notes->push_back(fmt::format("material and texture image dropped: {} cannot store them", fi.name));
  }
  return out;
}

// "..", an absolute path or a URI scheme ("http:", "file:"): a reference `files_beside` does not follow.
bool leaves_folder(const std::filesystem::path& p, std::string_view reference) {
  if (p.is_absolute() || p.has_root_name() || p.has_root_directory()) return true;
  const std::size_t colon = reference.find(':');
  if (colon != std::string_view::npos && colon > 1 && reference.find('/') > colon) return true;
  return std::ranges::any_of(p, [](const std::filesystem::path& part) { return part == ".."; });
}

// "%20" → " ": URIs escape their bytes.
std::string unescape(std::string_view reference) {
  std::string out;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    const auto hex = [&](std::size_t k) {
      return std::isxdigit(static_cast<unsigned char>(reference[k])) != 0;
    };
    if (reference[i] == '%' && i + 2 < reference.size() && hex(i + 1) && hex(i + 2)) {
      out.push_back(static_cast<char>(std::stoi(std::string(reference.substr(i + 1, 2)), nullptr, 16)));
      i += 2;
    } else {
      out.push_back(reference[i]);
    }
  }
  return out;
}

} // namespace

std::span<const FormatInfo> all_formats() { return kFormats; }

const FormatInfo& info(Format format) { return kFormats[static_cast<std::size_t>(format)]; }

std::optional<Format> format_from_path(const std::filesystem::path& path) {
  const std::string ext = lowercase(path.extension().string());
  for (const FormatInfo& fi : kFormats)
    if (std::ranges::find(fi.extensions, ext) != fi.extensions.end()) return fi.format;
  return std::nullopt;
}

Result<Format> format_from_name(std::string_view name) {
  std::string dotted = "." + lowercase(std::string(name));
  for (const FormatInfo& f : kFormats)
    if (std::ranges::find(f.extensions, dotted) != f.extensions.end()) return f.format;
  return make_error(ErrorCode::UnsupportedFormat,
                    fmt::format("unknown format '{}' (one of {})", name, extension_list()));
}

std::vector<std::string> format_names() {
  std::vector<std::string> out;
  for (const FormatInfo& f : kFormats)
    for (std::string_view e : f.extensions)
      out.emplace_back(e.substr(1));
  return out;
}

std::optional<Format> format_from_content(std::string_view bytes) {
  if (bytes.starts_with("#VRML")) return Format::Vrml;
  if (bytes.starts_with("glTF")) return Format::Glb;
  if (bytes.starts_with("DRACO")) return Format::Draco;
  if (bytes.starts_with(pdef::kMagic)) return Format::Pdef;
  if (bytes.starts_with("ply\n") || bytes.starts_with("ply\r")) return Format::Ply;
  if (bytes.starts_with("OFF") || bytes.starts_with("NOFF") || bytes.starts_with("COFF") ||
      bytes.starts_with("STOFF"))
    return Format::Off;
  const std::string_view text = skip_space(bytes);
  if (text.starts_with("{") && text.find("\"asset\"") != std::string_view::npos) return Format::Gltf;
  if (starts_with_ci(text, "solid") && text.find("facet") != std::string_view::npos) return Format::Stl;
  if (text.starts_with("v ") || text.starts_with("mtllib") || text.starts_with("o ") ||
      text.starts_with("g ") || (text.starts_with("#") && text.find("\nv ") != std::string_view::npos))
    return Format::Obj;
  return std::nullopt;
}

namespace {

// The format `read_mesh` reads `bytes` as: the options', else the content's, else the extension's (with a
// note when content and extension disagree).
Result<Format> format_to_read(std::string_view bytes, std::string_view source, const ReadOptions& options,
                              Notes* notes) {
  const std::optional<Format> by_name = format_from_path(std::filesystem::path(source));
  std::optional<Format> format = options.format;
  if (!format) {
    const std::optional<Format> by_content = format_from_content(bytes);
    auto same_family = [](Format a, Format b) {
      auto family = [](Format f) { return f == Format::Glb ? Format::Gltf : f; };
      return family(a) == family(b);
    };
    if (by_content && by_name && !same_family(*by_content, *by_name) && notes)
      notes->push_back(fmt::format("{}: the content is {}, not {} as the extension says", source,
                                   info(*by_content).name, info(*by_name).name));
    format = by_content ? by_content : by_name;
  }
  if (!format) {
    if (bytes.empty()) return make_error(ErrorCode::Empty, "the file is empty", std::string(source));
    return make_error(ErrorCode::UnsupportedFormat,
                      fmt::format("unknown format: neither the extension nor the content names one we read "
                                  "({})",
                                  extension_list()),
                      std::string(source));
  }
  return *format;
}

} // namespace

Result<LoadedMesh> read_mesh(std::string_view bytes, std::string_view source, const ReadOptions& options,
                             Notes* notes) {
  const Result<Format> format = format_to_read(bytes, source, options, notes);
  if (!format) return format.error();
  Result<Mesh> mesh = decode(*format, bytes, source, options, notes);
  if (!mesh) return std::move(mesh).error();
  if (mesh->name.empty()) mesh->name = std::filesystem::path(source).stem().string();
  return LoadedMesh{std::move(mesh).value(), *format, bytes.size()};
}

Resolver files_beside(const std::filesystem::path& file, std::uint64_t max_bytes) {
  return [folder = file.parent_path(), max_bytes](std::string_view reference) -> Result<std::string> {
    const std::string name = unescape(reference);
    const std::filesystem::path relative = std::filesystem::path(name).lexically_normal();
    if (name.empty() || leaves_folder(relative, name))
      return make_error(ErrorCode::UnsupportedFormat,
                        "only files in the folder of the file that names them are read",
                        clean_name(reference));
    const std::filesystem::path path = folder / relative;
    if (std::error_code ec; !std::filesystem::is_regular_file(path, ec))
      return make_error(ErrorCode::Io, "no such file", source_name(path));
    // A symbolic link out of the folder is not followed either.
    std::error_code ec;
    const std::filesystem::path real = std::filesystem::weakly_canonical(path, ec);
    const std::filesystem::path base = std::filesystem::weakly_canonical(folder.empty() ? "." : folder, ec);
    if (ec || std::ranges::mismatch(base, real).in1 != base.end())
      return make_error(ErrorCode::UnsupportedFormat, "a link to a file outside the folder is not followed",
                        source_name(path));
    return read_file(path, max_bytes);
  };
}

namespace {

// `options`, with the files beside `path` as the resolver when it has none and follows references.
ReadOptions resolving_beside(ReadOptions options, const std::filesystem::path& path) {
  if (!options.resolver && options.companions)
    options.resolver = files_beside(path, options.max_companion_bytes);
  return options;
}

} // namespace

Result<LoadedMesh> read_mesh(const std::filesystem::path& path, const ReadOptions& options, Notes* notes) {
  Result<std::string> bytes = read_file(path);
  if (!bytes) return std::move(bytes).error();
  return read_mesh(*bytes, source_name(path), resolving_beside(options, path), notes);
}

Result<std::vector<OutputFile>> encode_files(const Mesh& mesh, const std::filesystem::path& path,
                                             const WriteOptions& options, Notes* notes) {
  const std::string source = source_name(path);
  const std::optional<Format> format = options.format ? options.format : format_from_path(path);
  if (!format)
    return make_error(ErrorCode::UnsupportedFormat,
                      fmt::format("cannot tell the output format from the extension '{}' (use {})",
                                  path.extension().string(), extension_list()),
                      source);
  const FormatInfo& fi = info(*format);
  if (!fi.writable)
    return make_error(
        ErrorCode::UnsupportedFormat,
        fmt::format("a mesh cannot be written as {}: it holds a face's curves, made from a scan "
                    "(`pdeface encode SCAN -o FILE.pdef`)",
                    fi.extensions.front()),
        source);
  if (Result<void> valid = check_writable(mesh); !valid) return std::move(valid).error();
  if (mesh.is_point_cloud() && !fi.point_clouds)
    return make_error(ErrorCode::InvalidArgument,
                      fmt::format("{} cannot hold a point cloud (the mesh has no triangles)", fi.name),
                      source);
  std::optional<Mesh> storage;
  const Mesh& fitted = fit_to(fi, mesh, storage, notes);
  const drc::WriteOptions draco_options{.position_bits = options.draco_bits,
                                        .color_bits = options.draco_color_bits,
                                        .texcoord_bits = options.draco_uv_bits,
                                        .level = options.draco_level};
  // The files beside: the image (when its bytes were read; else the file refers to its old name), and
  // for OBJ the material library.
  std::vector<OutputFile> files(1);
  files[0].path = path;
  std::string image_name;
  if (fitted.material && fitted.material->base_color_image && *format != Format::Gltf &&
      *format != Format::Glb) {
    const Image& image = *fitted.material->base_color_image;
    const std::string stem = path.stem().string();
    if (!image.bytes.empty() && image_mime_type(image.bytes)) {
      image_name = stem + std::string(image_extension(image.mime_type));
      files.push_back({path.parent_path() / image_name, image.bytes});
    } else if (!image.uri.empty()) {
      image_name = image.uri;
      if (notes)
        notes->push_back(fmt::format("texture image '{}' referred to, not written: its bytes were not read",
                                     excerpt(image.uri)));
    }
  }
  if (*format == Format::Obj && fitted.material) {
    const std::string library = path.stem().string() + ".mtl";
    files.insert(files.begin() + 1,
                 OutputFile{path.parent_path() / library, obj::write_material_library(fitted, image_name)});
  }
  if (*format == Format::Draco || options.draco_in_gltf) {
    if (Result<void> ok = drc::check(draco_options); !ok) {
      Error e = std::move(ok).error();
      e.source = source;
      return e;
    }
  }

  Result<std::string> bytes = [&]() -> Result<std::string> {
    switch (*format) {
    case Format::Vrml: return vrml::write(fitted, {.texture_url = image_name}, notes);
    case Format::Obj:
      return obj::write(fitted,
                        {.material_library = fitted.material ? path.stem().string() + ".mtl" : std::string()},
                        notes);
    case Format::Ply:
      return ply::write(fitted, {.binary = !options.ascii, .texture_file = image_name}, notes);
    case Format::Off: return off::write(fitted, notes);
    case Format::Stl: return stl::write(fitted, {.binary = !options.ascii}, notes);
    case Format::Gltf:
    case Format::Glb:
      return gltf::write(fitted,
                         {.binary = *format == Format::Glb,
                          .draco = options.draco_in_gltf ? std::optional(draco_options) : std::nullopt},
                         notes);
    case Format::Draco: return drc::write(fitted, draco_options, notes);
    case Format::Pdef: break; // not writable: refused above
    }
    return make_error(ErrorCode::UnsupportedFormat, "unknown format", source);
  }();
  if (!bytes) return with_source(std::move(bytes).error(), source);
  files[0].bytes = std::move(bytes).value();
  return files;
}

Result<std::string> encode_mesh(const Mesh& mesh, const std::filesystem::path& path,
                                const WriteOptions& options, Notes* notes) {
  Result<std::vector<OutputFile>> files = encode_files(mesh, path, options, notes);
  if (!files) return std::move(files).error();
  return std::move(files->front().bytes);
}

Result<std::size_t> write_mesh(const Mesh& mesh, const std::filesystem::path& path,
                               const WriteOptions& options, Notes* notes) {
  Result<std::vector<OutputFile>> files = encode_files(mesh, path, options, notes);
  if (!files) return std::move(files).error();
  if (Result<void> written = write_files_atomic(*files); !written) return std::move(written).error();
  return files->front().bytes.size();
}

namespace {

// Whether every value is finite: the exponent bits tested as integers, without a branch or a 64-bit
// comparison (an exponent of all ones plus one carries into the sign bit), so that the loop vectorises
// even on SSE2 (std::isfinite stops at the first bad value and does not).
bool all_finite(std::span<const double> values) {
  constexpr std::uint64_t kExponent = 0x7ff0000000000000, kOne = 0x0010000000000000, kCarry = 1ULL << 63;
  std::uint64_t infinite = 0;
  for (const double v : values)
    infinite |= ((std::bit_cast<std::uint64_t>(v) & kExponent) + kOne) & kCarry;
  return infinite == 0;
}

// A .pdef file as binary PLY, written as it is made: the surface's rows a block at a time, each block with
// its mirror image (rows v and π − v share their product) written at its place in the file, then the
// triangles; never the whole mesh (at a million vertices 60 MB as a Mesh, 50 MB as PLY, and as many page
// faults). The bytes are those read_mesh + write_mesh give, and so are the errors.
Result<ConvertReport> stream_pdef_as_ply(std::string_view bytes, const std::filesystem::path& in,
                                         const std::filesystem::path& out, const ReadOptions& options) {
  const std::string source = source_name(in);
  Result<pdef::Face> face = pdef::decode(bytes, source);
  if (!face) return std::move(face).error();
  Result<pde::Surface> surface = pdef::surface_of(*face, source);
  if (!surface) return std::move(surface).error();
  std::optional<pdef::Resolution> grid;
  if (options.surface_u != 0 || options.surface_v != 0)
    grid = pdef::Resolution{options.surface_u, options.surface_v};
  Result<pde::GridMesher> mesher = pdef::scan_mesher(*face, *surface, grid, source);
  if (!mesher) return std::move(mesher).error();
  const ply::BinaryLayout layout{mesher->vertex_count(), mesher->triangle_count(), true,
                                 face->frame.scan_units};
  Result<AtomicFile> file = AtomicFile::create(out);
  if (!file) return std::move(file).error();
  const std::string header = ply::binary_header(layout);
  if (Result<void> written = file->append(header); !written) return std::move(written).error();

  // Blocks of 256 KiB stay in the caches and cost few page faults: 1 MiB ones made the 100k-vertex decode
  // 1.6x slower in the whole process (27.1 -> 16.5 ms), the 1M-vertex one 1.3x (43.7 -> 33.9 ms); 64 KiB
  // ones are slower again (40 ms: more calls, the same bytes).
  constexpr std::size_t kBlockBytes = std::size_t{1} << 18;
  const std::size_t nu = mesher->u_count(), nv = mesher->v_count(), half = (nv + 1) / 2;
  const std::size_t row_bytes = ply::binary_vertex_bytes(nu, true);
  const std::size_t rows = std::clamp<std::size_t>(kBlockBytes / row_bytes, 1, half);
  const std::size_t cell_rows =
      std::clamp<std::size_t>(kBlockBytes / ply::binary_triangle_bytes(2 * (nu - 1)), 1, nv - 1);
  std::vector<char> buffer(
      std::max(2 * rows * row_bytes, ply::binary_triangle_bytes(2 * (nu - 1) * cell_rows)));
  std::vector<Vec3> positions(2 * rows * nu);
  std::vector<Vec3f> normals(2 * rows * nu);
  const std::string name = face->name.empty() ? in.stem().string() : face->name;
  // Rows [first, first + count) made (`blocks`) are converted and written at their place.
  const auto write_rows = [&](std::span<const pde::GridMesher::RowBlock> blocks) -> Result<void> {
    mesher->rows(blocks);
    for (const pde::GridMesher::RowBlock& b : blocks) {
      if (b.count == 0) continue;
      if (!all_finite({b.positions.data()->data(), 3 * b.positions.size()})) {
        const auto bad = std::ranges::find_if(b.positions, [](const Vec3& p) { return !p.allFinite(); });
        return make_error(
            ErrorCode::NonFinite, // what validate() says of the mesh (a hostile frame's overflow)
            fmt::format("vertex {} has a non-finite coordinate",
                        b.first * nu + static_cast<std::size_t>(bad - b.positions.begin())),
            name);
      }
      const std::span<char> records = std::span(buffer).first(b.count * row_bytes);
      ply::put_binary_vertices(records, b.positions, b.normals);
      if (Result<void> written =
              file->write_at(header.size() + b.first * row_bytes, {records.data(), records.size()});
          !written)
        return written;
    }
    return {};
  };
  for (std::size_t first = 0; first < half; first += rows) {
    const std::size_t count = std::min(rows, half - first);
    const std::size_t mirror = std::max(nv - first - count, first + count), mirrored = nv - first - mirror;
    const std::span<Vec3> p(positions);
    const std::span<Vec3f> n(normals);
    const pde::GridMesher::RowBlock blocks[] = {
        {first, count, p.first(count * nu), n.first(count * nu)},
        {mirror, mirrored, p.subspan(count * nu, mirrored * nu), n.subspan(count * nu, mirrored * nu)}};
    if (Result<void> written = write_rows(blocks); !written) return std::move(written).error();
  }
  std::vector<Triangle> triangles(2 * (nu - 1) * cell_rows);
  std::uint64_t at = header.size() + nv * row_bytes;
  for (std::size_t k = 0; k + 1 < nv; k += cell_rows) {
    const std::size_t count = std::min(cell_rows, nv - 1 - k);
    const std::span<Triangle> t = std::span(triangles).first(2 * (nu - 1) * count);
    mesher->triangles(k, count, t);
    const std::span<char> records = std::span(buffer).first(ply::binary_triangle_bytes(t.size()));
    ply::put_binary_triangles(records, t);
    if (Result<void> written = file->write_at(at, {records.data(), records.size()}); !written)
      return std::move(written).error();
    at += records.size();
  }
  if (Result<void> committed = file->commit(); !committed) return std::move(committed).error();
  return ConvertReport{Format::Pdef,    Format::Ply,      bytes.size(), ply::binary_size(layout),
                       layout.vertices, layout.triangles, layout.units};
}

} // namespace

Result<ConvertReport> convert(const std::filesystem::path& in, const std::filesystem::path& out,
                              const ReadOptions& read_options, const WriteOptions& write_options,
                              Notes* notes) {
  Result<std::string> bytes = read_file(in);
  if (!bytes) return std::move(bytes).error();
  const Result<Format> from = format_to_read(*bytes, source_name(in), read_options, notes);
  if (!from) return from.error();
  const Format to = write_options.format ? *write_options.format : format_from_path(out).value_or(*from);
  if (*from == Format::Pdef && read_options.pdef_max_bytes != 0)
    bytes->resize(std::min(bytes->size(), read_options.pdef_max_bytes));
  // A residual layer moves every vertex along the normals of its neighbours' rows: made whole, not streamed.
  const bool residual = bytes->size() > 4 && static_cast<std::uint8_t>((*bytes)[4]) >= 3;
  if (*from == Format::Pdef && to == Format::Ply && !write_options.ascii && !residual)
    return stream_pdef_as_ply(*bytes, in, out, read_options);
  ReadOptions read = resolving_beside(read_options, in);
  read.format = *from;
  Result<LoadedMesh> loaded = read_mesh(*bytes, source_name(in), read, notes);
  if (!loaded) return std::move(loaded).error();
  Result<std::size_t> written = write_mesh(loaded->mesh, out, write_options, notes);
  if (!written) return std::move(written).error();
  return ConvertReport{loaded->format,
                       to,
                       loaded->bytes,
                       *written,
                       loaded->mesh.vertex_count(),
                       loaded->mesh.triangle_count(),
                       loaded->mesh.units};
}

} // namespace pdeface::formats

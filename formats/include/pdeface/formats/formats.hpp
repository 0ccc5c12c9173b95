#pragma once
//! \file
//! Reading and writing any supported format by file name: the format is chosen by extension (and, for
//! reading, checked against the content), bytes are parsed in memory, and files are written atomically.

#include "pdeface/core/file.hpp"
#include "pdeface/core/image.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace pdeface::formats {

enum class Format { Vrml, Obj, Ply, Off, Stl, Gltf, Glb, Draco, Pdef };

//! What a format is and what it can hold.
struct FormatInfo {
  Format format;
  std::string_view name;                        //!< "VRML", "PLY", ...
  std::span<const std::string_view> extensions; //!< lowercase, with the dot; the first is canonical
  bool faces = true;                            //!< can hold triangles (all can hold points)
  bool point_clouds = true;                     //!< can hold vertices without faces
  bool normals = false;
  bool colors = false;
  bool texcoords = false;
  bool lossy = false; //!< positions are quantised (Draco) or the surface is rebuilt (.pdef)
  bool writable =
      true; //!< `encode_mesh` writes it (not .pdef: a face's curves come from a scan, `pdeface encode`)
  bool materials = false; //!< keeps a material and its base-colour image (embedded, or a file beside it)
};

//! Every format, in a stable order.
[[nodiscard]] std::span<const FormatInfo> all_formats();
[[nodiscard]] const FormatInfo& info(Format format);
//! The format an extension names (case-insensitive), if any.
[[nodiscard]] std::optional<Format> format_from_path(const std::filesystem::path& path);
//! The format an extension without its dot names ("ply", "GLB"). Errors: `UnsupportedFormat` listing the
//! extensions there are.
[[nodiscard]] Result<Format> format_from_name(std::string_view name);
//! Every extension without its dot ("wrl", "vrml", "obj", ...), for a command line's choices.
[[nodiscard]] std::vector<std::string> format_names();
//! The format the first bytes identify (magic numbers and headers), if any. OBJ and STL have no magic
//! and are only recognised by the most likely first statement.
[[nodiscard]] std::optional<Format> format_from_content(std::string_view bytes);

struct ReadOptions {
  std::optional<Format> format; //!< override detection
  //! `.pdef`: the grid its surface is evaluated on, u × v ({0, v}: v points along the face's height and as
  //! many across as keep the cells square; {0, 0}: about 1 mm between points).
  std::size_t surface_u = 0;
  std::size_t surface_v = 0;
  //! `.pdef`: read only the file's first bytes (0: all): a version 3 file cut in its residual layer
  //! decodes to a coarser surface (docs/pdef-format.md).
  std::size_t pdef_max_bytes = 0;
  //! Where the files a mesh file refers to (OBJ's material library and its image, glTF's and VRML's image
  //! files) come from. Empty: `read_mesh(path)` reads them beside the file (`files_beside`), `read_mesh`
  //! of bytes leaves them out with a note.
  Resolver resolver;
  //! Follow such references at all (false: each is a note).
  bool companions = true;
  //! The most bytes a referenced file may have (`files_beside`).
  std::uint64_t max_companion_bytes = std::uint64_t{64} << 20;
};

//! A resolver reading the files a file at `file` refers to, relative to its folder: a relative path that
//! stays inside that folder (no `..` above it, no absolute path, no URI scheme; `%XX` escapes decoded), of
//! at most `max_bytes`. Errors (notes to the reader): `UnsupportedFormat` for a reference it will not
//! follow, `Io` and `CountTooLarge` from `read_file`.
[[nodiscard]] Resolver files_beside(const std::filesystem::path& file,
                                    std::uint64_t max_bytes = std::uint64_t{64} << 20);

struct LoadedMesh {
  Mesh mesh;
  Format format;
  std::size_t bytes = 0; //!< size of the file read
};

//! Reads a mesh or point cloud. The format comes from `options.format`, else the content, else the
//! extension; a file whose content contradicts its extension is read by its content, with a note.
[[nodiscard]] Result<LoadedMesh> read_mesh(const std::filesystem::path& path, const ReadOptions& options = {},
                                           Notes* notes = nullptr);
//! The same from bytes in memory; `source` names them in errors and picks the format by extension.
[[nodiscard]] Result<LoadedMesh> read_mesh(std::string_view bytes, std::string_view source,
                                           const ReadOptions& options = {}, Notes* notes = nullptr);

struct WriteOptions {
  std::optional<Format> format; //!< override the extension
  bool ascii = false;           //!< PLY and STL: ASCII instead of binary
  bool draco_in_gltf = false;   //!< GLB: compress with KHR_draco_mesh_compression
  int draco_bits = 14;          //!< Draco and Draco-in-glTF: position quantisation bits (1..24)
  int draco_level = 7;          //!< Draco compression level (0..10; 0 keeps vertex order)
  int draco_uv_bits = 12;       //!< Draco: texture coordinate quantisation bits (1..24; `draco_encoder -qt`)
  int draco_color_bits = 8;     //!< Draco: colours as normalised integers of 8 or 16 bits
};

//! Encodes a mesh in the format of `path` (or `options.format`). Attributes the format cannot hold are
//! dropped, each with a note. Errors: `UnsupportedFormat`, `InvalidArgument`, errors from the encoder.
[[nodiscard]] Result<std::string> encode_mesh(const Mesh& mesh, const std::filesystem::path& path,
                                              const WriteOptions& options = {}, Notes* notes = nullptr);

//! Every file a mesh is written as: the file at `path` first, then what it refers to beside it. OBJ: a
//! material library `<stem>.mtl` and the image `<stem>.jpg` (or `.png`); PLY and VRML: the image
//! `<stem>.jpg`, named in the file (a PLY `comment TextureFile`, a VRML `ImageTexture` url). An image the
//! mesh names but whose bytes were not read is referred to by its name, not written (a note says so).
//! Errors: those of `encode_mesh`.
[[nodiscard]] Result<std::vector<OutputFile>> encode_files(const Mesh& mesh,
                                                           const std::filesystem::path& path,
                                                           const WriteOptions& options = {},
                                                           Notes* notes = nullptr);

//! `encode_files`, then an atomic write of them all (`write_files_atomic`): on any error no file is left
//! at `path` or beside it. Returns the bytes of the file at `path`.
[[nodiscard]] Result<std::size_t> write_mesh(const Mesh& mesh, const std::filesystem::path& path,
                                             const WriteOptions& options = {}, Notes* notes = nullptr);

struct ConvertReport {
  Format from;
  Format to;
  std::size_t bytes_in = 0;
  std::size_t bytes_out = 0;
  std::size_t vertices = 0;
  std::size_t triangles = 0;
  Units units = Units::Unknown; //!< the mesh's
};

//! `read_mesh(in)` then `write_mesh(out)`: what `pdeface convert` and `pdeface decode` do. A `.pdef` to
//! binary PLY is streamed instead: the surface made and written a block of rows at a time, never held
//! whole (the same bytes, the same errors; a million vertices in ~1 MiB of memory).
[[nodiscard]] Result<ConvertReport> convert(const std::filesystem::path& in, const std::filesystem::path& out,
                                            const ReadOptions& read_options = {},
                                            const WriteOptions& write_options = {}, Notes* notes = nullptr);

} // namespace pdeface::formats

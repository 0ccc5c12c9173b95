#pragma once
// The PLY header, parsed exactly, and a check of the data against it.
//
// The validator (`check_data`) builds no mesh; `read_direct` reads the usual layouts in one pass instead,
// and gives up where the validator would refuse. It exists because OpenMesh's PLY reader hangs on a header
// without end_header, crashes on a property before any element, allocates without bound on a lying
// count, and reads words, "nan" and missing data as zeros without saying where
// (third_party_notes/openmesh.md). Parsing the header and walking the data once gives exact errors: the
// header line and column, the byte offset in binary data, the line and column in ASCII data. It also
// hands OpenMesh only what OpenMesh reads correctly: a canonical header of the vertex and face elements,
// then their data.

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace pdeface::ply::detail {

enum class Encoding { Ascii, BinaryLittleEndian, BinaryBigEndian };
enum class Scalar { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

//! What the reader does with a property's values.
enum class Role {
  Ignored,    //!< skipped (with a note)
  Coordinate, //!< position, normal or texture coordinate: read as float, must be finite
  Color,      //!< vertex or face colour
  Indices,    //!< the face's vertex_indices list: every entry must name a vertex
};

struct Property {
  std::string name;
  std::string label;                //!< the name as messages quote it (`excerpt`)
  Scalar type = Scalar::Float32;    //!< of the value, or of a list's entries
  std::optional<Scalar> count_type; //!< set for list properties
  Role role = Role::Ignored;
  std::uint64_t line = 0;
};

struct Element {
  std::string name;
  std::string label; //!< the name as messages quote it (`excerpt`)
  std::uint64_t count = 0;
  std::vector<Property> properties;
  std::uint64_t line = 0;
};

struct Header {
  Encoding encoding = Encoding::Ascii;
  std::vector<Element> elements;
  Units units = Units::Unknown; //!< from a "comment units mm" line
  std::string texture_file;     //!< from a "comment TextureFile name.jpg" line (MeshLab's)
  std::size_t data_offset = 0;  //!< first byte after the end_header line
  std::uint64_t data_line = 0;  //!< line on which the data starts (ASCII)
};

//! The bytes of one binary value of `type`.
[[nodiscard]] std::size_t size_of(Scalar type);

//! Whether `e.count` records of the smallest size its properties allow (empty lists, one-character ASCII
//! values) fit in `file_size` bytes: a count beyond is refused before anything is read or allocated.
[[nodiscard]] bool count_fits(const Element& e, Encoding encoding, std::size_t file_size);

//! Parses the header and checks that OpenMesh reads what it declares (property types, lists, a vertex
//! element with x, y, z). Notes what will be ignored.
[[nodiscard]] Result<Header> parse_header(std::string_view bytes, std::string_view source, Notes* notes);

//! The data of the vertex and face elements (empty if there is none).
struct DataRanges {
  std::string_view vertices;
  std::string_view faces;
};

//! Walks every element of the data: each value present and of its type, coordinates finite, face
//! indices in range. Errors carry the byte offset (binary) or line and column (ASCII).
[[nodiscard]] Result<DataRanges> check_data(const Header& header, std::string_view bytes,
                                            std::string_view source, Notes* notes);

//! The data read straight into a mesh, for the layouts whose reading through OpenMesh is known value for
//! value: float x y z [nx ny nz] [u v | s t | texture_u texture_v], uchar red green blue [alpha], other
//! vertex properties of any type; faces' vertex_indices with a uchar or int length and (u)char or (u)int
//! entries, other face properties (not colours) of any type; any other elements. The same mesh as
//! OpenMesh gives, in one pass over the bytes.
struct DirectRead {
  Mesh mesh;
  std::size_t short_faces = 0;                //!< fewer than three corners: skipped
  std::size_t data_end = 0;                   //!< binary: the first byte after the last element
  std::optional<std::uint64_t> trailing_line; //!< ASCII: the line of data after the last element
};

//! nullopt when the layout is not one of those, or at the first value the validator (`check_data`)
//! refuses: it then names the fault. Checks everything `check_data` checks: a mesh means it would pass.
[[nodiscard]] std::optional<DirectRead> read_direct(const Header& header, std::string_view bytes);

//! What OpenMesh reads: a canonical header (vertex then face element, "\n" line ends, no comments,
//! texture_u/texture_v renamed to the u/v OpenMesh knows) followed by the two elements' data.
[[nodiscard]] std::string openmesh_input(const Header& header, const DataRanges& data);

} // namespace pdeface::ply::detail

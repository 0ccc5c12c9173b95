#pragma once
// The PLY header, parsed exactly, and a check of the data against it.
//
// This is a validator, not a second reader: it builds no mesh. It exists because OpenMesh's PLY reader
// hangs on a header without end_header, crashes on a property before any element, allocates without
// bound on a lying count, and reads words, "nan" and missing data as zeros without saying where
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
  std::size_t data_offset = 0;  //!< first byte after the end_header line
  std::uint64_t data_line = 0;  //!< line on which the data starts (ASCII)
};

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

//! What OpenMesh reads: a canonical header (vertex then face element, "\n" line ends, no comments,
//! texture_u/texture_v renamed to the u/v OpenMesh knows) followed by the two elements' data.
[[nodiscard]] std::string openmesh_input(const Header& header, const DataRanges& data);

} // namespace pdeface::ply::detail

// The entry point: the header line decides the version, a parser builds the scene, the builder the mesh.

#include "build.hpp"
#include "context.hpp"
#include "parse_v1.hpp"
#include "parse_v2.hpp"
#include "pdeface/core/text.hpp"

#include "pdeface/vrml/vrml.hpp"

#include <fmt/format.h>

namespace pdeface::vrml {
namespace {

using detail::Context;
using detail::Position;
using detail::Version;

struct Header {
  Version version;
  Position body; // where the parser starts (the header line itself lexes as a comment)
};

//! The next run of non-blank characters on the header line from `pos`; `start` is where it begins.
std::string_view header_word(std::string_view line, std::size_t& pos, std::size_t& start) {
  while (pos < line.size() && (line[pos] == ' ' || line[pos] == '\t'))
    ++pos;
  start = pos;
  while (pos < line.size() && line[pos] != ' ' && line[pos] != '\t')
    ++pos;
  return line.substr(start, pos - start);
}

// "#VRML V2.0 utf8" or "#VRML V1.0 ascii", maybe after a UTF-8 byte order mark, maybe followed by more
// text (which the specifications allow).
Header read_header(std::string_view bytes, const Context& context) {
  if (bytes.empty()) context.fail(ErrorCode::Empty, Position{}, "the file is empty");
  const std::size_t bom = bytes.starts_with("\xEF\xBB\xBF") ? 3 : 0;
  const std::string_view line = bytes.substr(0, bytes.find_first_of("\r\n"));
  auto at = [&](std::size_t pos) { return Position{pos, 1, pos - bom + 1}; };
  std::size_t pos = bom, magic_at = bom, version_at = bom, encoding_at = bom;
  if (header_word(line, pos, magic_at) != "#VRML" || magic_at != bom)
    context.fail(ErrorCode::BadMagic, at(bom),
                 "not a VRML file: expected the header '#VRML V2.0 utf8' or '#VRML V1.0 ascii'");
  const std::string_view version = header_word(line, pos, version_at);
  const std::string_view encoding = header_word(line, pos, encoding_at);
  const bool v1 = version == "V1.0";
  if (!v1 && version != "V2.0")
    context.fail(ErrorCode::UnsupportedVersion, at(version_at),
                 version.empty() ? std::string("the header names no version: expected V1.0 or V2.0")
                                 : fmt::format("VRML version '{}' is not supported: expected V1.0 or V2.0",
                                               excerpt(version)));
  const std::string_view expected = v1 ? "ascii" : "utf8";
  if (encoding != expected)
    context.fail(ErrorCode::UnsupportedVersion, at(encoding_at),
                 fmt::format("encoding '{}' is not supported for VRML {}: expected {}", excerpt(encoding),
                             version, expected));
  return {v1 ? Version::V1 : Version::V2, Position{bom, 1, 1}};
}

} // namespace

Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes, const Resolver& resolve) {
  Context context(bytes, source);
  try {
    const Header header = read_header(bytes, context);
    detail::Scene scene = header.version == Version::V1 ? detail::ParserV1(context, header.body).parse()
                                                        : detail::ParserV2(context, header.body).parse();
    Mesh mesh = detail::build_mesh(scene, header.version, context);
    if (Result<void> valid = validate(mesh, source); !valid) return std::move(valid).error();
    context.flush_notes(notes);
    if (mesh.material && mesh.material->base_color_image) {
      Result<Image> image = resolve_image(resolve, mesh.material->base_color_image->uri, source, notes);
      if (!image) return std::move(image).error();
      mesh.material->base_color_image = std::move(image).value();
    }
    return mesh;
  } catch (const detail::Failure& failure) {
    return failure.error;
  }
}

} // namespace pdeface::vrml

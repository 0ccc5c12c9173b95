// The texture layer of a .pdef file: an ancillary section holding one JPEG image over the surface's (u, v)
// domain, kept byte for byte, skipped by a reader of shape alone, and refused with its byte when broken.

#include "pdeface/image/image.hpp"
#include "pdeface/pdef/mesh.hpp"
#include "pdeface/pdef/pdef.hpp"

#include "pdef_support.hpp"

#include <gtest/gtest.h>

namespace pdeface::pdef {
namespace {

using test::synthetic_face;
using test::with_checksum;

Image jpeg(std::uint32_t width = 40, std::uint32_t height = 30) {
  image::Pixels p{width, height, std::vector<std::uint8_t>(std::size_t{width} * height * 3)};
  for (std::size_t i = 0; i < p.rgb.size(); ++i)
    p.rgb[i] = static_cast<std::uint8_t>((i * 7) % 251);
  return {image::encode_jpeg(p), "image/jpeg", {}};
}

Face textured() {
  Face face = synthetic_face();
  face.texture = jpeg();
  return face;
}

// Where the texture section's tag is (the last section before the checksum).
std::size_t texture_at(const std::string& bytes) {
  const Result<std::vector<Section>> parts = sections(bytes);
  for (const Section& s : parts.value())
    if (s.name == "texture") return s.offset;
  ADD_FAILURE() << "no texture section";
  return 0;
}

TEST(PdefTexture, TheImageIsKeptByteForByteAndSkippedOnRequest) {
  const Face face = textured();
  for (const bool lossless : {false, true}) {
    const std::string bytes = encode(face, {.lossless = lossless}).value().bytes;
    const Result<Face> back = decode(bytes, "t.pdef");
    ASSERT_TRUE(back.ok()) << back.error().to_string();
    ASSERT_TRUE(back->texture);
    EXPECT_EQ(back->texture->bytes, face.texture->bytes);
    EXPECT_EQ(back->texture->mime_type, "image/jpeg");
    const Result<Face> shape = decode(bytes, "t.pdef", {.texture = false});
    ASSERT_TRUE(shape.ok());
    EXPECT_FALSE(shape->texture);
    EXPECT_EQ(shape->curves.samples, back->curves.samples);
    // Without the layer the file is the curve-only file with the section taken out.
    Face plain = face;
    plain.texture.reset();
    const std::string without = encode(plain, {.lossless = lossless}).value().bytes;
    EXPECT_EQ(bytes.size(), without.size() + 2 + 1 + face.texture->bytes.size() + 1) // tag, length, codec
        << "a 2-byte length for this image";
  }
}

// Adding the layer to a written file gives the bytes of encoding the face with it; a file that has one,
// a version 3 file, or an image that is not JPEG are refused.
TEST(PdefTexture, WithTextureIsEncodingWithIt) {
  Face plain = textured();
  const Image texture = *plain.texture;
  plain.texture.reset();
  for (const bool lossless : {false, true}) {
    const std::string curves = encode(plain, {.lossless = lossless}).value().bytes;
    const Result<std::string> added = with_texture(curves, texture);
    ASSERT_TRUE(added.ok()) << added.error().to_string();
    EXPECT_TRUE(*added == encode(textured(), {.lossless = lossless}).value().bytes);
    EXPECT_FALSE(with_texture(*added, texture)) << "a second layer";
    EXPECT_FALSE(with_texture(curves, Image{"not a jpeg", "image/jpeg", {}}));
    std::string v3 = curves;
    v3[4] = 3;
    EXPECT_FALSE(with_texture(with_checksum(v3), texture));
  }
}

TEST(PdefTexture, TheMeshTakesTheGridsTextureCoordinatesAndTheImage) {
  const Face face = decode(encode(textured()).value().bytes).value();
  const Result<Mesh> mesh = to_mesh(face, Resolution{11, 21});
  ASSERT_TRUE(mesh.ok());
  ASSERT_EQ(mesh->texcoords.size(), mesh->vertex_count());
  EXPECT_TRUE(mesh->texcoord_triangles.empty());
  EXPECT_EQ(mesh->texcoords[0], Vec2f(0, 0));
  EXPECT_EQ(mesh->texcoords[10], Vec2f(1, 0));
  EXPECT_TRUE(mesh->texcoords[20 * 11 + 5].isApprox(Vec2f(0.5f, 1.0f)));
  ASSERT_TRUE(mesh->material && mesh->material->base_color_image);
  EXPECT_EQ(mesh->material->base_color_image->bytes, face.texture->bytes);
  Mesh copy = *mesh;
  EXPECT_THROW(with_texture(copy, 10, 21, *face.texture), std::invalid_argument);
  Face plain = face;
  plain.texture.reset();
  EXPECT_TRUE(to_mesh(plain, Resolution{11, 21})->texcoords.empty());
}

TEST(PdefTexture, OnlyAJpegImageIsEncoded) {
  Face face = textured();
  face.texture->bytes = std::string("\x89PNG\r\n\x1a\n", 8) + std::string(30, '\0');
  Result<Encoded> e = encode(face);
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().code, ErrorCode::InvalidArgument);
  face.texture->bytes = "not an image";
  EXPECT_FALSE(encode(face));
}

// The section replaced by `content` (a one- or two-byte length), the file's length and checksum fixed.
std::string with_texture_content(const std::string& bytes, std::string_view content) {
  const std::size_t at = texture_at(bytes);
  std::string out = bytes.substr(0, at);
  out += static_cast<char>(0x80);
  std::size_t n = content.size();
  do {
    out += static_cast<char>((n & 0x7f) | (n >= 0x80 ? 0x80 : 0));
    n >>= 7;
  } while (n != 0);
  out += content;
  out += bytes.substr(bytes.size() - 4);
  const auto length = static_cast<std::uint32_t>(out.size());
  for (int i = 0; i < 4; ++i)
    out[6 + static_cast<std::size_t>(i)] = static_cast<char>(length >> (8 * i));
  return with_checksum(out);
}

TEST(PdefTexture, BrokenLayersAreRefusedAtTheirByteAndSkippedByShapeReaders) {
  const std::string bytes = encode(textured()).value().bytes;
  const std::size_t at = texture_at(bytes);
  const std::string image = textured().texture->bytes;
  struct Case {
    std::string content;
    ErrorCode code;
    std::size_t where; // from the section's content
  };
  const std::size_t content = at + 3; // tag and a two-byte length
  const Case cases[] = {
      {std::string(1, '\x02') + image, ErrorCode::Malformed, 0},                    // an unknown codec
      {std::string(1, '\x01') + "GIF89a........", ErrorCode::UnsupportedFormat, 1}, // not a JPEG
      {std::string(1, '\x01') + image.substr(0, 10), ErrorCode::Truncated, 1},
  };
  for (const Case& c : cases) {
    const std::string hostile = with_texture_content(bytes, c.content);
    const Result<Face> r = decode(hostile, "hostile.pdef");
    ASSERT_FALSE(r) << c.content.size();
    EXPECT_EQ(r.error().code, c.code) << r.error().to_string();
    ASSERT_TRUE(r.error().where.byte);
    const std::size_t start = hostile[at + 1] & 0x80 ? content : content - 1;
    EXPECT_GE(*r.error().where.byte, start + c.where) << r.error().to_string();
    EXPECT_EQ(r.error().source, "hostile.pdef");
    EXPECT_TRUE(decode(hostile, "hostile.pdef", {.texture = false}).ok()) << "a shape reader skips it";
  }
  // An empty section, and a second one.
  const Result<Face> empty = decode(with_texture_content(bytes, ""), "e.pdef");
  ASSERT_FALSE(empty);
  EXPECT_EQ(empty.error().code, ErrorCode::Malformed);
  std::string twice = bytes;
  const std::string section = bytes.substr(at, bytes.size() - 4 - at);
  twice.insert(bytes.size() - 4, section);
  const auto length = static_cast<std::uint32_t>(twice.size());
  for (int i = 0; i < 4; ++i)
    twice[6 + static_cast<std::size_t>(i)] = static_cast<char>(length >> (8 * i));
  const Result<Face> second = decode(with_checksum(twice), "twice.pdef");
  ASSERT_FALSE(second);
  EXPECT_EQ(second.error().code, ErrorCode::Malformed);
  EXPECT_EQ(second.error().where.byte, bytes.size() - 4);
}

TEST(PdefTexture, AnImageDeclaringTooManyPixelsIsRefused) {
  // A JPEG whose frame header declares 65535 × 65535 pixels (a decompression bomb) is refused from its
  // header: nothing is decoded.
  std::string image = textured().texture->bytes;
  const std::size_t sof = image.find("\xff\xc0", 2);
  ASSERT_NE(sof, std::string::npos);
  for (const std::size_t i : {sof + 5, sof + 6, sof + 7, sof + 8})
    image[i] = '\xff';
  const std::string bytes = encode(textured()).value().bytes;
  const Result<Face> r = decode(with_texture_content(bytes, std::string(1, '\x01') + image), "bomb.pdef");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::CountTooLarge) << r.error().to_string();
}

// tests/data/pdef/textured.pdef (the synthetic face with a 16 × 12 JPEG; also a seed of pdef_fuzz): read,
// meshed with its texture, and written again byte for byte.
TEST(PdefTexture, TheFixtureDecodesMeshesAndEncodesAgainToItsBytes) {
  const std::string file = test::slurp(test::fixtures() / "pdef" / "textured.pdef");
  const Result<Face> face = decode(file, "textured.pdef");
  ASSERT_TRUE(face.ok()) << face.error().to_string();
  ASSERT_TRUE(face->texture);
  const Result<ImageInfo> info = inspect_image(face->texture->bytes, "texture");
  ASSERT_TRUE(info.ok());
  EXPECT_EQ(info->width, 16U);
  EXPECT_EQ(info->height, 12U);
  const Result<Mesh> mesh = to_mesh(*face);
  ASSERT_TRUE(mesh.ok());
  EXPECT_EQ(mesh->texcoords.size(), mesh->vertex_count());
  EXPECT_EQ(encode(*face, {.max_error_mm = face->storage.step_mm}).value().bytes, file);
}

} // namespace
} // namespace pdeface::pdef

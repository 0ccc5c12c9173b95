#include "pdeface/core/image.hpp"

#include "pdeface/core/text.hpp"

#include <fmt/format.h>

namespace pdeface {
namespace {

constexpr std::string_view kPngSignature{"\x89PNG\r\n\x1a\n", 8};

std::uint32_t load_be(std::string_view bytes, std::size_t at, std::size_t width) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < width; ++i)
    v = (v << 8) | static_cast<std::uint8_t>(bytes[at + i]);
  return v;
}

Error image_error(ErrorCode code, std::string message, std::string_view source, std::size_t at) {
  return make_error(code, std::move(message), std::string(source), Location::at_byte(at));
}

Result<ImageInfo> check_size(ImageInfo info, std::string_view source, std::size_t at, std::uint64_t max) {
  if (info.width == 0 || info.height == 0)
    return image_error(ErrorCode::Malformed,
                       fmt::format("an image of {} × {} pixels", info.width, info.height), source, at);
  if (std::uint64_t{info.width} * info.height > max)
    return image_error(ErrorCode::CountTooLarge,
                       fmt::format("an image of {} × {} pixels: more than the {} pixels we accept",
                                   info.width, info.height, max),
                       source, at);
  return info;
}

Result<ImageInfo> inspect_png(std::string_view bytes, std::string_view source, std::uint64_t max) {
  // Signature (8), then the IHDR chunk: length 13 (4), "IHDR" (4), width (4), height (4), ... (5), CRC (4).
  constexpr std::size_t kIhdr = 8, kEnd = 8 + 8 + 13 + 4;
  if (bytes.size() < kEnd)
    return image_error(ErrorCode::Truncated, "the PNG ends inside its header", source, bytes.size());
  if (load_be(bytes, kIhdr, 4) != 13 || bytes.substr(kIhdr + 4, 4) != "IHDR")
    return image_error(ErrorCode::Malformed, "the PNG does not start with its IHDR chunk", source, kIhdr);
  return check_size({"image/png", load_be(bytes, kIhdr + 8, 4), load_be(bytes, kIhdr + 12, 4)}, source,
                    kIhdr + 8, max);
}

// Start-of-frame markers: C0..CF but DHT (C4), JPG (C8) and DAC (CC).
bool frame_marker(std::uint8_t m) { return m >= 0xC0 && m <= 0xCF && m != 0xC4 && m != 0xC8 && m != 0xCC; }

Result<ImageInfo> inspect_jpeg(std::string_view bytes, std::string_view source, std::uint64_t max) {
  std::size_t at = 2; // after SOI
  for (;;) {
    if (at >= bytes.size())
      return image_error(ErrorCode::Truncated, "the JPEG ends before its frame header", source, at);
    if (static_cast<std::uint8_t>(bytes[at]) != 0xFF)
      return image_error(ErrorCode::Malformed, "expected a JPEG marker", source, at);
    while (at < bytes.size() && static_cast<std::uint8_t>(bytes[at]) == 0xFF) // fill bytes
      ++at;
    if (at >= bytes.size())
      return image_error(ErrorCode::Truncated, "the JPEG ends before its frame header", source, at);
    const auto marker = static_cast<std::uint8_t>(bytes[at]);
    const std::size_t segment = at + 1;
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) { // no length
      at = segment;
      continue;
    }
    if (marker == 0xD8 || marker == 0xD9 || marker == 0xDA || marker == 0x00)
      return image_error(ErrorCode::Malformed,
                         fmt::format("JPEG marker 0x{:02X} before the frame header", marker), source, at - 1);
    if (segment + 2 > bytes.size())
      return image_error(ErrorCode::Truncated, "the JPEG ends inside a marker segment", source, segment);
    const std::uint32_t length = load_be(bytes, segment, 2);
    if (length < 2)
      return image_error(ErrorCode::Malformed, fmt::format("a JPEG segment of length {}", length), source,
                         segment);
    if (segment + length > bytes.size())
      return image_error(ErrorCode::Truncated, "the JPEG ends inside a marker segment", source, segment);
    if (frame_marker(marker)) {
      // precision (1), height (2), width (2), components (1)
      if (length < 8)
        return image_error(ErrorCode::Malformed, "a JPEG frame header too short", source, segment);
      return check_size({"image/jpeg", load_be(bytes, segment + 5, 2), load_be(bytes, segment + 3, 2)},
                        source, segment + 3, max);
    }
    at = segment + length;
  }
}

} // namespace

std::optional<std::string_view> image_mime_type(std::string_view bytes) noexcept {
  if (bytes.starts_with("\xFF\xD8\xFF")) return "image/jpeg";
  if (bytes.starts_with(kPngSignature)) return "image/png";
  return std::nullopt;
}

std::string_view image_extension(std::string_view mime_type) noexcept {
  if (mime_type == "image/jpeg") return ".jpg";
  if (mime_type == "image/png") return ".png";
  return ".bin";
}

Result<ImageInfo> inspect_image(std::string_view bytes, std::string_view source, std::uint64_t max_pixels) {
  const std::optional<std::string_view> mime = image_mime_type(bytes);
  if (!mime) return image_error(ErrorCode::UnsupportedFormat, "not a JPEG or PNG image", source, 0);
  return *mime == "image/png" ? inspect_png(bytes, source, max_pixels)
                              : inspect_jpeg(bytes, source, max_pixels);
}

Result<Image> resolve_image(const Resolver& resolve, std::string_view reference, std::string_view source,
                            Notes* notes) {
  Image image;
  image.uri = reference;
  auto note = [&](std::string_view why) {
    if (notes)
      notes->push_back(fmt::format("{}: texture image '{}' not read ({}); its name is kept", source,
                                   excerpt(reference), why));
  };
  if (!resolve) {
    note("reading from memory: no folder to find it in");
    return image;
  }
  Result<std::string> bytes = resolve(reference);
  if (!bytes) {
    note(bytes.error().message);
    return image;
  }
  if (!image_mime_type(*bytes)) {
    note("neither JPEG nor PNG, the images glTF holds");
    return image;
  }
  Result<ImageInfo> info = inspect_image(*bytes, clean_name(reference));
  if (!info) return std::move(info).error();
  image.mime_type = info->mime_type;
  image.bytes = std::move(bytes).value();
  return image;
}

} // namespace pdeface

// Images decoded, sampled, resized and encoded: JPEG through libjpeg-turbo's TurboJPEG API, PNG decoded by
// stb_image (third_party_notes/libjpeg-turbo.md, stb.md).

#include "pdeface/image/image.hpp"

#include <fmt/format.h>
#include <turbojpeg.h>

#define STBI_ONLY_PNG
#define STBI_NO_STDIO
#define STBI_NO_LINEAR
#define STBI_NO_HDR
#define STBI_MAX_DIMENSIONS 8192
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

namespace pdeface::image {
namespace {

Error decode_error(std::string message, std::string_view source) {
  return make_error(ErrorCode::Malformed, std::move(message), std::string(source), Location::at_byte(0));
}

struct Decompressor {
  tjhandle handle = tjInitDecompress();
  ~Decompressor() {
    if (handle) tjDestroy(handle);
  }
  Decompressor() = default;
  Decompressor(const Decompressor&) = delete;
  Decompressor& operator=(const Decompressor&) = delete;
};

Result<Pixels> decode_jpeg(std::string_view bytes, const ImageInfo& info, std::string_view source) {
  Decompressor d;
  if (!d.handle) throw std::runtime_error("image: libjpeg-turbo could not start a decompressor");
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const auto size = static_cast<unsigned long>(bytes.size());
  int width = 0, height = 0, subsampling = 0, colorspace = 0;
  if (tjDecompressHeader3(d.handle, data, size, &width, &height, &subsampling, &colorspace) != 0)
    return decode_error(fmt::format("a JPEG image libjpeg-turbo cannot read: {}", tjGetErrorStr2(d.handle)),
                        source);
  if (static_cast<std::uint32_t>(width) != info.width || static_cast<std::uint32_t>(height) != info.height)
    return decode_error(fmt::format("a JPEG image of {} × {} pixels by its frame header but {} × {} to "
                                    "libjpeg-turbo",
                                    info.width, info.height, width, height),
                        source);
  Pixels out{info.width, info.height, std::vector<std::uint8_t>(std::size_t{info.width} * info.height * 3)};
  if (tjDecompress2(d.handle, data, size, out.rgb.data(), width, 0, height, TJPF_RGB,
                    TJFLAG_ACCURATEDCT | TJFLAG_STOPONWARNING) != 0)
    return decode_error(fmt::format("a corrupt JPEG image: {}", tjGetErrorStr2(d.handle)), source);
  return out;
}

Result<Pixels> decode_png(std::string_view bytes, const ImageInfo& info, std::string_view source) {
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    return decode_error("a PNG image of more than 2 GB", source);
  int width = 0, height = 0, channels = 0;
  const std::unique_ptr<stbi_uc, decltype(&stbi_image_free)> data(
      stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), static_cast<int>(bytes.size()),
                            &width, &height, &channels, 3),
      &stbi_image_free);
  if (!data) return decode_error(fmt::format("a corrupt PNG image: {}", stbi_failure_reason()), source);
  if (static_cast<std::uint32_t>(width) != info.width || static_cast<std::uint32_t>(height) != info.height)
    return decode_error("a PNG image whose size is not its header's", source);
  Pixels out{info.width, info.height, {}};
  out.rgb.assign(data.get(), data.get() + std::size_t{info.width} * info.height * 3);
  return out;
}

} // namespace

Eigen::Vector3f Pixels::at(std::uint32_t x, std::uint32_t y) const {
  const std::size_t i = (std::size_t{y} * width + x) * 3;
  return Eigen::Vector3f(rgb[i], rgb[i + 1], rgb[i + 2]) / 255.0f;
}

Result<Pixels> decode(std::string_view bytes, std::string_view source, std::uint64_t max_pixels) {
  Result<ImageInfo> info = inspect_image(bytes, source, max_pixels);
  if (!info) return std::move(info).error();
  return info->mime_type == "image/png" ? decode_png(bytes, *info, source)
                                        : decode_jpeg(bytes, *info, source);
}

Result<Pixels> decode(const Image& image, std::string_view source) { return decode(image.bytes, source); }

std::string encode_jpeg(const Pixels& pixels, const JpegOptions& options) {
  if (pixels.empty() || pixels.rgb.size() != std::size_t{pixels.width} * pixels.height * 3)
    throw std::invalid_argument("image::encode_jpeg: an empty image or one whose size is not its pixels'");
  if (options.quality < 1 || options.quality > 100)
    throw std::invalid_argument(fmt::format("image::encode_jpeg: quality {} (1-100)", options.quality));
  const std::unique_ptr<void, decltype(&tjDestroy)> handle(tjInitCompress(), &tjDestroy);
  if (!handle) throw std::runtime_error("image: libjpeg-turbo could not start a compressor");
  unsigned char* out = nullptr;
  unsigned long size = 0;
  const int failed =
      tjCompress2(handle.get(), pixels.rgb.data(), static_cast<int>(pixels.width), 0,
                  static_cast<int>(pixels.height), TJPF_RGB, &out, &size,
                  options.subsample ? TJSAMP_420 : TJSAMP_444, options.quality, TJFLAG_ACCURATEDCT);
  const std::unique_ptr<unsigned char, decltype(&tjFree)> owned(out, &tjFree);
  if (failed != 0)
    throw std::runtime_error(fmt::format("image: libjpeg-turbo: {}", tjGetErrorStr2(handle.get())));
  return {reinterpret_cast<const char*>(out), static_cast<std::size_t>(size)};
}

Eigen::Vector3f sample(const Pixels& pixels, const Vec2f& st) {
  if (pixels.empty()) throw std::invalid_argument("image::sample: an empty image");
  // Pixel centres at (x + 0.5) / width across and, from the top, (y + 0.5) / height.
  const float fx = std::clamp(st.x(), 0.0f, 1.0f) * static_cast<float>(pixels.width) - 0.5f;
  const float fy = (1.0f - std::clamp(st.y(), 0.0f, 1.0f)) * static_cast<float>(pixels.height) - 0.5f;
  const auto cell = [](float f, std::uint32_t n) {
    const float c = std::clamp(f, 0.0f, static_cast<float>(n - 1));
    const auto i = std::min(static_cast<std::uint32_t>(c), n - 1);
    return std::pair{i, std::min(i + 1, n - 1)};
  };
  const auto [x0, x1] = cell(fx, pixels.width);
  const auto [y0, y1] = cell(fy, pixels.height);
  const float ax = std::clamp(fx - static_cast<float>(x0), 0.0f, 1.0f);
  const float ay = std::clamp(fy - static_cast<float>(y0), 0.0f, 1.0f);
  const Eigen::Vector3f top = (1 - ax) * pixels.at(x0, y0) + ax * pixels.at(x1, y0);
  const Eigen::Vector3f bottom = (1 - ax) * pixels.at(x0, y1) + ax * pixels.at(x1, y1);
  return (1 - ay) * top + ay * bottom;
}

Pixels resized(const Pixels& pixels, std::uint32_t width, std::uint32_t height) {
  if (pixels.empty() || width == 0 || height == 0)
    throw std::invalid_argument("image::resized: an empty image or a zero size");
  Pixels out{width, height, std::vector<std::uint8_t>(std::size_t{width} * height * 3)};
  const double sx = static_cast<double>(pixels.width) / width,
               sy = static_cast<double>(pixels.height) / height;
  for (std::uint32_t y = 0; y < height; ++y) {
    const double y0 = y * sy, y1 = (y + 1) * sy;
    for (std::uint32_t x = 0; x < width; ++x) {
      const double x0 = x * sx, x1 = (x + 1) * sx;
      std::array<double, 3> sum{};
      double area = 0;
      for (auto py = static_cast<std::uint32_t>(y0); py < std::min<double>(y1, pixels.height); ++py) {
        const double wy = std::min<double>(py + 1, y1) - std::max<double>(py, y0);
        for (auto px = static_cast<std::uint32_t>(x0); px < std::min<double>(x1, pixels.width); ++px) {
          const double w = wy * (std::min<double>(px + 1, x1) - std::max<double>(px, x0));
          const std::size_t i = (std::size_t{py} * pixels.width + px) * 3;
          for (int c = 0; c < 3; ++c)
            sum[static_cast<std::size_t>(c)] += w * pixels.rgb[i + static_cast<std::size_t>(c)];
          area += w;
        }
      }
      const std::size_t o = (std::size_t{y} * width + x) * 3;
      for (std::size_t c = 0; c < 3; ++c)
        out.rgb[o + c] = static_cast<std::uint8_t>(std::clamp(std::lround(sum[c] / area), 0L, 255L));
    }
  }
  return out;
}

float to_srgb(float linear) {
  const float c = std::clamp(linear, 0.0f, 1.0f);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

float to_linear(float srgb) {
  const float c = std::clamp(srgb, 0.0f, 1.0f);
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

} // namespace pdeface::image

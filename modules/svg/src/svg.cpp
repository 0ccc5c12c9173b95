#include "pdeface/svg/svg.hpp"

#include "pdeface/core/depth_map.hpp"

#include <fmt/format.h>

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace pdeface::svg {
namespace {

std::string base64(const std::string& bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 3; ++k)
      v = (v << 8U) | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0U);
    for (std::size_t k = 0; k < 4; ++k)
      out += k <= n ? kAlphabet[(v >> (18U - 6U * k)) & 0x3FU] : '=';
  }
  return out;
}

std::string png(const std::vector<unsigned char>& pixels, int width, int height, int channels) {
  std::string out;
  stbi_write_png_to_func(
      [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                                   static_cast<std::size_t>(size));
      },
      &out, width, height, channels, pixels.data(), width * channels);
  return out;
}

} // namespace

std::string escape(std::string_view text) {
  std::string out;
  for (char c : text) {
    switch (c) {
    case '<': out += "&lt;"; break;
    case '>': out += "&gt;"; break;
    case '&': out += "&amp;"; break;
    default: out += c;
    }
  }
  return out;
}

std::string front_view_image(const Mesh& canonical, const FrontViewBox& box) {
  return front_view_image(canonical, box, {});
}

std::string front_view_image(const Mesh& canonical, const FrontViewBox& box, const Colouring& colour) {
  DepthMap map(box.x0, box.x1, box.y0, box.y1, box.pixel_mm);
  map.rasterise(canonical.positions, canonical.triangles, 1.5);

  // Lambert shading of the depth map's normals, light from the upper left front; white where nothing is.
  const int w = map.cols(), h = map.rows();
  const int channels = colour ? 3 : 1;
  std::vector<unsigned char> pixels(static_cast<std::size_t>(w) * h * channels, 255);
  const Vec3 light = Vec3(-0.4, 0.5, 0.77).normalized();
  for (int r = 1; r + 1 < h; ++r)
    for (int c = 1; c + 1 < w; ++c) {
      if (!map.known(r, c)) continue;
      auto z = [&](int rr, int cc) { return map.known(rr, cc) ? map.z(rr, cc) : map.z(r, c); };
      const double dx = (z(r, c + 1) - z(r, c - 1)) / (2 * map.cell());
      const double dy = (z(r + 1, c) - z(r - 1, c)) / (2 * map.cell());
      const double shade = std::max(0.0, Vec3(-dx, -dy, 1.0).normalized().dot(light));
      const std::size_t at = (static_cast<std::size_t>(h - 1 - r) * w + c) * channels; // rows top-down
      if (!colour) {
        pixels[at] = static_cast<unsigned char>(40 + 200 * shade);
        continue;
      }
      const Eigen::Vector3f rgb = colour(Vec3(map.x_of(c), map.y_of(r), map.z(r, c)));
      for (int k = 0; k < 3; ++k)
        pixels[at + k] =
            static_cast<unsigned char>(std::clamp(255.0 * rgb[k] * (0.35 + 0.65 * shade), 0.0, 255.0));
    }
  return fmt::format("<image x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" "
                     "href=\"data:image/png;base64,{}\"/>\n",
                     box.x0, -box.y1, box.x1 - box.x0, box.y1 - box.y0, base64(png(pixels, w, h, channels)));
}

} // namespace pdeface::svg

#include "pdeface/align/preview.hpp"

#include "depth_map.hpp"

#include <fmt/format.h>

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace pdeface::align {
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

std::string png(const std::vector<unsigned char>& grey, int width, int height) {
  std::string out;
  stbi_write_png_to_func(
      [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                                   static_cast<std::size_t>(size));
      },
      &out, width, height, 1, grey.data(), width);
  return out;
}

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

} // namespace

std::string preview_svg(const Mesh& scan, const FaceFrame& frame, const Landmarks& landmarks,
                        const PreviewOptions& options) {
  const Mesh face = to_canonical(scan, frame);
  constexpr double kX0 = -110.0, kX1 = 110.0, kY0 = -150.0, kY1 = 130.0; // mm around the nose tip
  detail::DepthMap map(kX0, kX1, kY0, kY1, options.pixel_mm);
  map.rasterise(face.positions, face.triangles, 1.5);

  // Lambert shading of the depth map's normals, light from the upper left front.
  const int w = map.cols(), h = map.rows();
  std::vector<unsigned char> grey(static_cast<std::size_t>(w) * h, 255);
  const Vec3 light = Vec3(-0.4, 0.5, 0.77).normalized();
  for (int r = 1; r + 1 < h; ++r)
    for (int c = 1; c + 1 < w; ++c) {
      if (!map.known(r, c)) continue;
      auto z = [&](int rr, int cc) { return map.known(rr, cc) ? map.z(rr, cc) : map.z(r, c); };
      const double dx = (z(r, c + 1) - z(r, c - 1)) / (2 * map.cell());
      const double dy = (z(r + 1, c) - z(r - 1, c)) / (2 * map.cell());
      const double shade = std::max(0.0, Vec3(-dx, -dy, 1.0).normalized().dot(light));
      grey[static_cast<std::size_t>(h - 1 - r) * w + c] =
          static_cast<unsigned char>(40 + 200 * shade); // rows top-down
    }

  const double width_mm = kX1 - kX0, height_mm = kY1 - kY0;
  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"{} {} {} {}\" width=\"{}\" height=\"{}\" "
      "font-family=\"sans-serif\">\n",
      kX0, -kY1, width_mm, height_mm + 14, 2 * width_mm, 2 * (height_mm + 14));
  svg +=
      fmt::format("<image x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" href=\"data:image/png;base64,{}\"/>\n",
                  kX0, -kY1, width_mm, height_mm, base64(png(grey, w, h)));
  svg += fmt::format("<line x1=\"0\" y1=\"{}\" x2=\"0\" y2=\"{}\" stroke=\"#1f77b4\" stroke-width=\"0.6\" "
                     "stroke-dasharray=\"3 2\"/>\n",
                     -kY1, -kY0);
  const Landmarks canonical = to_canonical(landmarks, frame);
  for (std::size_t i = 0; i < kLandmarkCount; ++i) {
    if (!canonical.points[i]) continue;
    const Vec3& p = *canonical.points[i];
    const bool midline = mirrored(static_cast<Landmark>(i)) == static_cast<Landmark>(i);
    svg += fmt::format(
        "<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"2\" fill=\"{}\" stroke=\"white\" stroke-width=\"0.5\"/>\n",
        p.x(), -p.y(), midline ? "#d62728" : "#ff7f0e");
    svg += fmt::format("<text x=\"{:.2f}\" y=\"{:.2f}\" font-size=\"4\" fill=\"#d62728\">{}</text>\n",
                       p.x() + 3, -p.y() - 2, name(static_cast<Landmark>(i)));
  }
  svg += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"6\">{}</text>\n</svg>\n", kX0 + 3, -kY0 + 10,
                     escape(options.title));
  return svg;
}

} // namespace pdeface::align

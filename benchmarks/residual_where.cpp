// Where a `.pdef` with a residual layer is farthest from its scan: `residual_where OUT SCAN BUDGET...`
// encodes SCAN at each budget as `pdeface encode --size` does, measures mesh → scan as `pdeface compare`
// does (samples of the decoded mesh in the face mask where the scan shows surface from the front), prints
// the worst points and writes OUT/<scan>_<budget>.ppm (front view, 0.25 mm a pixel, each pixel the worst
// sample over it, blue 0 … red --scale mm; grey: the scan's front, black: nothing) and
// OUT/<scan>_<budget>_N.svg (sections through the N-th worst cluster: across x = const (y–z) and y = const
// (x–z); black the scan, red the decoded mesh, grey the curves' surface, its normal lines at the nodes near
// the plane, green where they found the scan) and OUT/<scan>_<budget>_trim.pgm (the layer's cells, v up:
// black trimmed, white kept, grey kept with a corner whose line found no scan). It also prints the
// yardstick's figures both ways (mesh → scan, mask → mesh). `--spacing MM` sets the layer's grid.

#include "pdeface/align/pipeline.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface/metrics/fidelity.hpp"
#include "pdeface/metrics/front_view.hpp"
#include "pdeface/metrics/surface_distance.hpp"
#include "pdeface/pdef/mesh.hpp"
#include "pdeface/pdef/residual.hpp"
#include "pdeface/pipeline/encode.hpp"
#include "pdeface/pipeline/reconstruct.hpp"
#include "pdeface/residual/measure.hpp"
#include "pdeface/slice/intersect.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

using namespace pdeface;

namespace {

std::array<unsigned char, 3> heat(double d, double scale) {
  static const double stops[5][3] = {
      {0.16, 0.33, 0.80}, {0.15, 0.70, 0.85}, {0.56, 0.82, 0.27}, {0.98, 0.65, 0.14}, {0.80, 0.08, 0.10}};
  const double t = std::clamp(d / scale, 0.0, 1.0) * 4;
  const int i = std::min(3, static_cast<int>(t));
  const double f = t - i;
  std::array<unsigned char, 3> out{};
  for (int k = 0; k < 3; ++k)
    out[k] = static_cast<unsigned char>(255 * ((1 - f) * stops[i][k] + f * stops[i + 1][k]));
  return out;
}

struct Sample {
  double d;
  Vec3 p, near;
};

// Polylines of `mesh` cut by the plane, within the window, in the plane's 2D coordinates.
std::string polylines(const Mesh& mesh, const Plane& plane, int a, int b, const Vec3& c, double half,
                      const char* style) {
  std::string out;
  for (const Polyline& line : slice::intersect(mesh, plane)) {
    std::string path;
    bool pen = false;
    for (const Vec3& p : line.points) {
      const double x = p[a] - c[a], y = p[b] - c[b];
      if (std::abs(x) > half || std::abs(y) > half) {
        pen = false;
        continue;
      }
      path += fmt::format("{}{:.3f},{:.3f} ", pen ? "L" : "M", x, -y);
      pen = true;
    }
    if (!path.empty()) out += fmt::format("<path d=\"{}\" {}/>\n", path, style);
  }
  return out;
}

} // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    fmt::print("usage: residual_where OUT SCAN BUDGET... [--scale MM] [--spacing MM]\n");
    return 2;
  }
  const std::filesystem::path out_dir = argv[1];
  std::filesystem::create_directories(out_dir);
  const std::string path = argv[2];
  std::vector<std::size_t> budgets;
  double scale = 1.0, spacing = 0.0;
  for (int i = 3; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--scale" && i + 1 < argc)
      scale = std::atof(argv[++i]);
    else if (a == "--spacing" && i + 1 < argc)
      spacing = std::atof(argv[++i]);
    else
      budgets.push_back(std::stoul(a));
  }
  Result<formats::LoadedMesh> loaded = formats::read_mesh(path);
  if (!loaded) return 1;
  const Mesh& raw = loaded->mesh;
  Result<align::Alignment> alignment = align::align_scan(raw, std::nullopt, path);
  if (!alignment) return 1;
  const pipeline::CanonicalScan canonical = pipeline::canonical_scan(raw, *alignment);
  const Mesh& scan = canonical.mesh;
  Result<slice::ProfileSet> profiles = pipeline::extract_profiles(canonical);
  const slice::FaceMask& mask = profiles->mask;
  const double hw = mask.half_width + 1.0;
  const metrics::FrontView view(scan, -hw, hw, mask.centre_y - mask.half_height - 0.5,
                                mask.centre_y + mask.half_height + 0.5, 0.5);
  const metrics::SurfaceDistance to_scan(scan);
  const std::optional<metrics::FaceYardstick> yardstick =
      metrics::FaceYardstick::make(scan, *profiles).value();
  const std::string stem = std::filesystem::path(path).stem().string();
  for (const std::size_t budget : budgets) {
    pipeline::EncodeRequest request;
    request.check.reset();
    request.residual.size_bytes = budget;
    request.profiles.ratio = pipeline::default_ratio(request.residual);
    if (spacing > 0) request.residual.spacing_mm = spacing;
    Result<pipeline::EncodeOutcome> made = pipeline::encode_aligned(raw, *alignment, request);
    if (!made) {
      fmt::print("{}\n", made.error().to_string());
      return 1;
    }
    if (made->residual)
      fmt::print("  layer {} B, trim {} B whole ({:.2f} % of the cells), found {:.2f} %\n",
                 made->residual->layer_bytes, made->residual->trim_bytes, 100 * made->residual->trimmed_share,
                 100 * made->residual->found_share);
    Result<pdef::Face> face = pdef::decode(made->encoded.bytes);
    Result<Mesh> decoded = pdef::to_mesh(*face);
    { // decoding time, the best of 5: the file to a face, the face to its mesh on the layer's grid
      double parse = 1e9, meshing = 1e9;
      for (int run = 0; run < 5; ++run) {
        const auto t0 = std::chrono::steady_clock::now();
        const Result<pdef::Face> f = pdef::decode(made->encoded.bytes);
        const auto t1 = std::chrono::steady_clock::now();
        const Result<Mesh> m = pdef::to_mesh(*f);
        const auto t2 = std::chrono::steady_clock::now();
        parse = std::min(parse, std::chrono::duration<double, std::milli>(t1 - t0).count());
        meshing = std::min(meshing, std::chrono::duration<double, std::milli>(t2 - t1).count());
      }
      double untrimmed_ms = 1e9;
      pdef::Face whole = *face;
      if (whole.residual) whole.residual->trimmed.clear();
      for (int run = 0; run < 5; ++run) {
        const auto t0 = std::chrono::steady_clock::now();
        const Result<Mesh> m = pdef::to_mesh(whole);
        untrimmed_ms = std::min(
            untrimmed_ms,
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      }
      fmt::print(
          "  decode {:.2f} ms, mesh {:.2f} ms ({:.2f} ms without its trim; {} vertices, {} triangles)\n",
          parse, meshing, untrimmed_ms, decoded->vertex_count(), decoded->triangle_count());
    }
    Mesh mesh = align::to_canonical(*decoded, canonical.frame);
    Result<pde::Surface> surface = pdef::surface_of(*face);
    std::vector<std::uint8_t> found;
    std::size_t gw = 0, gh = 0;
    if (pdef::has_offsets(*face)) {
      gw = face->residual->field.width;
      gh = face->residual->field.height;
      const residual::Measured measured = residual::measure(*surface, scan, gw, gh);
      found = measured.found;
    }
    {
      const metrics::MeshFidelity f = yardstick->measure(mesh).value();
      fmt::print("  yardstick: mesh -> scan {:.4f} / {:.4f} / {:.3f}; mask -> mesh {:.4f} / {:.4f} / {:.3f}, "
                 "coverage {:.2f} %\n",
                 f.to_scan.mean, f.to_scan.p95, f.to_scan.max, f.coverage.distance.mean,
                 f.coverage.distance.p95, f.coverage.distance.max, 100 * f.coverage.share);
    }
    if (pdef::has_offsets(*face) && !face->residual->trimmed.empty()) { // the trim as an image, v up
      std::ofstream pgm(out_dir / fmt::format("{}_{}_trim.pgm", stem, budget), std::ios::binary);
      pgm << "P5\n" << gw - 1 << " " << gh - 1 << "\n255\n";
      for (std::size_t k = gh - 1; k-- > 0;)
        for (std::size_t i = 0; i + 1 < gw; ++i)
          pgm.put(static_cast<char>(
              face->residual->trimmed[k * (gw - 1) + i] ? 0 : (found[k * gw + i] ? 255 : 160)));
    }
    pdef::Face untrimmed = *face;
    if (untrimmed.residual) untrimmed.residual->trimmed.clear();
    const Mesh grid_mesh = align::to_canonical(*pdef::to_mesh(untrimmed), canonical.frame);
    pdef::Face bare = *face;
    bare.residual.reset();
    const Mesh base = align::to_canonical(
        *pdef::to_mesh(bare, gw ? std::optional(pdef::Resolution{gw, gh}) : std::nullopt), canonical.frame);
    std::vector<Sample> samples;
    for (const Vec3& p : metrics::sample_surface(mesh, 0.5))
      if (mask.contains(p) && view.sees_surface(p.x(), p.y())) {
        const metrics::SurfaceDistance::Nearest n = to_scan.nearest(p);
        samples.push_back({n.distance, p, n.point});
      }
    std::sort(samples.begin(), samples.end(), [](const Sample& a, const Sample& b) { return a.d > b.d; });
    double sum = 0;
    for (const Sample& s : samples)
      sum += s.d;
    fmt::print("{} {} B ({} B, grid {} x {}): {} samples, mean {:.4f}, p95 {:.4f}, max {:.3f}\n", stem,
               budget, made->encoded.bytes.size(), gw, gh, samples.size(),
               sum / static_cast<double>(samples.size()), samples[samples.size() / 20].d, samples.front().d);
    // Clusters of the worst: a sample 4 mm from every one kept before it.
    std::vector<Sample> worst;
    for (const Sample& s : samples) {
      if (worst.size() == 8 || s.d < 0.5 * samples.front().d) break;
      if (std::ranges::all_of(worst, [&](const Sample& w) { return (w.p - s.p).norm() > 4.0; }))
        worst.push_back(s);
    }
    std::size_t above[4] = {0, 0, 0, 0};
    for (const Sample& s : samples)
      for (int k = 0; k < 4; ++k)
        if (s.d > 0.25 * (1 << k)) ++above[k];
    fmt::print("  samples above 0.25/0.5/1/2 mm: {} {} {} {}\n", above[0], above[1], above[2], above[3]);
    for (std::size_t k = 0; k < worst.size(); ++k) {
      const Sample& s = worst[k];
      // The node of the layer's grid nearest to it (the mesh is the grid, vertex = node).
      std::size_t node = 0;
      double best = 1e300;
      for (std::size_t v = 0; v < grid_mesh.vertex_count(); ++v)
        if (const double e = (grid_mesh.positions[v] - s.p).squaredNorm(); e < best) best = e, node = v;
      const int f = found.empty() ? -1 : found[node];
      std::size_t found_near = 0, near_count = 0;
      if (gw)
        for (int dy = -3; dy <= 3; ++dy)
          for (int dx = -3; dx <= 3; ++dx) {
            const long i = static_cast<long>(node % gw) + dx, j = static_cast<long>(node / gw) + dy;
            if (i < 0 || j < 0 || i >= static_cast<long>(gw) || j >= static_cast<long>(gh)) continue;
            ++near_count;
            found_near += found[j * gw + i];
          }
      fmt::print("  #{} {:.3f} mm at ({:.2f}, {:.2f}, {:.2f}), scan's nearest ({:.2f}, {:.2f}, {:.2f}); node "
                 "({}, {}) found {} ({} of {} around)\n",
                 k, s.d, s.p.x(), s.p.y(), s.p.z(), s.near.x(), s.near.y(), s.near.z(), gw ? node % gw : 0,
                 gw ? node / gw : 0, f, found_near, near_count);
      // Sections through it.
      const double half = 8.0;
      std::string svg = fmt::format("<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {} {}\" "
                                    "width=\"1200\" height=\"600\"><rect width=\"100%\" height=\"100%\" "
                                    "fill=\"white\"/>\n",
                                    4 * half + 2, 2 * half);
      for (int panel = 0; panel < 2; ++panel) {
        const int a = panel == 0 ? 1 : 0; // the section's horizontal axis: y (x = const) or x (y = const)
        const Plane plane{panel == 0 ? Vec3::UnitX() : Vec3::UnitY(), panel == 0 ? s.p.x() : s.p.y()};
        svg +=
            fmt::format("<g transform=\"translate({} {})\">\n<text x=\"{}\" y=\"{}\" font-size=\"0.8\">{} = "
                        "{:.2f}; horizontal {}, vertical z; {:.3f} mm</text>\n",
                        half + panel * (2 * half + 2), half, -half, -half + 0.8, panel == 0 ? "x" : "y",
                        panel == 0 ? s.p.x() : s.p.y(), panel == 0 ? "y" : "x", s.d);
        svg += polylines(base, plane, a, 2, s.p, half,
                         "fill=\"none\" stroke=\"#999\" stroke-width=\"0.06\" stroke-dasharray=\"0.3 0.2\"");
        svg +=
            polylines(scan, plane, a, 2, s.p, half, "fill=\"none\" stroke=\"black\" stroke-width=\"0.08\"");
        svg += polylines(mesh, plane, a, 2, s.p, half, "fill=\"none\" stroke=\"red\" stroke-width=\"0.06\"");
        // The curves' surface's normal lines at nodes near the plane.
        if (gw) {
          const pde::NormalGrid g = pde::normal_grid(*surface, gw, gh);
          for (std::size_t v = 0; v < g.points.size(); ++v) {
            const Vec3 x = g.points[v];
            if (std::abs(x[panel == 0 ? 0 : 1] - plane.offset) > 0.3) continue;
            if (std::abs(x[a] - s.p[a]) > half || std::abs(x.z() - s.p.z()) > half) continue;
            const Vec3 e = x + 6.0 * g.normals[v], b = x - 6.0 * g.normals[v];
            svg += fmt::format("<line x1=\"{:.3f}\" y1=\"{:.3f}\" x2=\"{:.3f}\" y2=\"{:.3f}\" stroke=\"{}\" "
                               "stroke-width=\"0.02\"/>\n",
                               b[a] - s.p[a], -(b.z() - s.p.z()), e[a] - s.p[a], -(e.z() - s.p.z()),
                               found[v] ? "#6a6" : "#c6c");
          }
        }
        svg += fmt::format("<circle cx=\"0\" cy=\"0\" r=\"0.15\" fill=\"blue\"/><circle cx=\"{:.3f}\" "
                           "cy=\"{:.3f}\" r=\"0.12\" fill=\"green\"/>\n</g>\n",
                           s.near[a] - s.p[a], -(s.near.z() - s.p.z()));
      }
      svg += "</svg>\n";
      std::ofstream(out_dir / fmt::format("{}_{}_{}.svg", stem, budget, k)) << svg;
    }
    // The front view: grey where the scan shows surface, each sample's pixel its worst.
    const double px = 0.25, x0 = -1.1 * mask.half_width, y1 = mask.centre_y + 1.05 * mask.half_height;
    const int w = static_cast<int>(2.2 * mask.half_width / px),
              h = static_cast<int>(2.1 * mask.half_height / px);
    std::vector<double> worst_at(static_cast<std::size_t>(w * h), -1);
    for (const Sample& s : samples) {
      const int c = static_cast<int>((s.p.x() - x0) / px), r = static_cast<int>((y1 - s.p.y()) / px);
      if (c >= 0 && r >= 0 && c < w && r < h) worst_at[r * w + c] = std::max(worst_at[r * w + c], s.d);
    }
    std::ofstream ppm(out_dir / fmt::format("{}_{}.ppm", stem, budget), std::ios::binary);
    ppm << "P6\n" << w << " " << h << "\n255\n";
    for (int r = 0; r < h; ++r)
      for (int c = 0; c < w; ++c) {
        const double x = x0 + (c + 0.5) * px, y = y1 - (r + 0.5) * px;
        std::array<unsigned char, 3> rgb{0, 0, 0};
        if (worst_at[r * w + c] >= 0)
          rgb = heat(worst_at[r * w + c], scale);
        else if (view.sees_surface(x, y))
          rgb = {170, 170, 170};
        for (const Sample& s : worst)
          if (std::abs(s.p.x() - x) < 0.6 && std::abs(s.p.y() - y) < 0.6) rgb = {255, 0, 255};
        ppm.write(reinterpret_cast<const char*>(rgb.data()), 3);
      }
  }
}

// Rate and distortion of the `.pdef` residual layer on real scans, the measurements that chose its design
// (third_party_notes/residual.md): `residual_rd [--spacing MM] [--step MM] SCAN...` prints, per scan and byte
// budget, the file's size and the decoded surface's distances to the scan in the face mask (mm), as
// `pdeface compare` measures them, with the layer's decode time. `--dump DIR` writes instead, per scan, the
// measured field as a 16-bit PGM (the coder's finest step a unit, offset to be positive), its found mask as
// an 8-bit PGM and a JSON of what our coder reaches at each stream size (the offsets' RMS error on the
// found nodes), for tools/residual_codecs.py to set image codecs beside it at equal bytes.

#include "pdeface/align/pipeline.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface/metrics/fidelity.hpp"
#include "pdeface/pdef/mesh.hpp"
#include "pdeface/pdef/residual.hpp"
#include "pdeface/pipeline/encode.hpp"
#include "pdeface/pipeline/reconstruct.hpp"
#include "pdeface/residual/measure.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace pdeface;

int main(int argc, char** argv) {
  double spacing = 0.5, step = pdef::kDefaultResidualStep;
  std::vector<std::size_t> budgets{1024, 2048, 4096, 8192, 16384, 32768};
  std::vector<std::string> scans;
  std::string dump;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--dump" && i + 1 < argc)
      dump = argv[++i];
    else if (a == "--spacing" && i + 1 < argc)
      spacing = std::atof(argv[++i]);
    else if (a == "--step" && i + 1 < argc)
      step = std::atof(argv[++i]);
    else
      scans.push_back(a);
  }
  for (const std::string& path : scans) {
    Result<formats::LoadedMesh> loaded = formats::read_mesh(path);
    if (!loaded) {
      fmt::print("{}: {}\n", path, loaded.error().to_string());
      continue;
    }
    const Mesh& scan = loaded->mesh;
    Result<align::Alignment> alignment = align::align_scan(scan, std::nullopt, path);
    if (!alignment) {
      fmt::print("{}: {}\n", path, alignment.error().to_string());
      continue;
    }
    const pipeline::CanonicalScan canonical = pipeline::canonical_scan(scan, *alignment);
    Result<slice::ProfileSet> profiles = pipeline::extract_profiles(canonical);
    Result<metrics::FaceYardstick> yardstick = metrics::FaceYardstick::make(canonical.mesh, *profiles);
    pipeline::EncodeRequest request; // the curves `pdeface encode --size` puts under a layer
    request.profiles.ratio = pipeline::kResidualRatio;
    request.check.reset();
    Result<pipeline::EncodeOutcome> made = pipeline::encode_aligned(scan, *alignment, request);
    if (!made || !yardstick) {
      fmt::print("{}: failed\n", path);
      continue;
    }
    const std::string curves = made->encoded.bytes;
    Result<pdef::Face> face = pdef::decode(curves);
    Result<pde::Surface> surface = face ? pdef::surface_of(*face) : Result<pde::Surface>(face.error());
    if (!surface) {
      fmt::print("{}: {}\n", path, surface.error().to_string());
      continue;
    }
    const residual::GridSize size = residual::grid_for(*surface, spacing);
    auto t0 = std::chrono::steady_clock::now();
    const residual::Measured measured = residual::measure(*surface, canonical.mesh, size.width, size.height);
    auto t1 = std::chrono::steady_clock::now();
    Result<pdef::CodedResidual> coded = pdef::code_residual(measured.field, {.step_mm = step});
    auto t2 = std::chrono::steady_clock::now();
    if (!coded) { // a grid too fine for the curves' file (pdef::max_residual_nodes)
      fmt::print("{}: grid {} x {}: {}\n", path, size.width, size.height, coded.error().to_string());
      continue;
    }
    fmt::print("{}: curves {} B, grid {} x {}, found {:.1f} %, stream {} B at {} mm ({} planes, {} levels); "
               "measure {:.0f} ms, code {:.0f} ms\n",
               path, curves.size(), size.width, size.height, 100 * measured.found_share(),
               coded->stream.size(), step, coded->planes, coded->levels,
               std::chrono::duration<double, std::milli>(t1 - t0).count(),
               std::chrono::duration<double, std::milli>(t2 - t1).count());
    if (!dump.empty()) { // the field, its mask and our coder's RMS at each stream size
      const pde::Displacement& field = measured.field;
      double lo = 0;
      for (double v : field.values)
        lo = std::min(lo, v);
      const std::string stem = (std::filesystem::path(dump) / std::filesystem::path(path).stem()).string();
      std::ofstream pgm(stem + ".pgm", std::ios::binary), mask(stem + ".mask.pgm", std::ios::binary);
      pgm << "P5\n" << field.width << " " << field.height << "\n65535\n";
      mask << "P5\n" << field.width << " " << field.height << "\n255\n";
      for (std::size_t p = 0; p < field.values.size(); ++p) {
        const auto q = static_cast<long>(std::lround((field.values[p] - lo) / step));
        const auto u = static_cast<unsigned>(std::clamp(q, 0L, 65535L));
        pgm.put(static_cast<char>(u >> 8));
        pgm.put(static_cast<char>(u & 0xff));
        mask.put(static_cast<char>(measured.found[p] ? 255 : 0));
      }
      std::string ours;
      for (const std::size_t bytes : {512UL, 1024UL, 2048UL, 4096UL, 8192UL, 16384UL, 32768UL}) {
        const pde::Displacement back = pdef::decode_residual(*coded, bytes);
        double sum = 0;
        std::size_t n = 0;
        for (std::size_t p = 0; p < field.values.size(); ++p)
          if (measured.found[p]) {
            sum += std::pow(back.values[p] - field.values[p], 2);
            ++n;
          }
        ours += fmt::format("{}{{\"bytes\": {}, \"rms_mm\": {:.6g}}}", ours.empty() ? "" : ", ", bytes,
                            std::sqrt(sum / static_cast<double>(std::max<std::size_t>(n, 1))));
      }
      std::ofstream(stem + ".json") << fmt::format(
          "{{\"scan\": \"{}\", \"width\": {}, \"height\": {}, \"step_mm\": {}, \"offset_mm\": {}, "
          "\"found\": {:.4f}, \"ours\": [{}]}}\n",
          path, field.width, field.height, step, lo, measured.found_share(), ours);
      continue;
    }
    auto report = [&](std::string_view label, const std::string& bytes) {
      auto s = std::chrono::steady_clock::now();
      Result<pdef::Face> f = pdef::decode(bytes);
      if (!f) {
        fmt::print("  {}: {}\n", label, f.error().to_string());
        return;
      }
      auto m = std::chrono::steady_clock::now();
      Result<Mesh> mesh = pdef::to_mesh(*f);
      auto e = std::chrono::steady_clock::now();
      Result<metrics::MeshFidelity> fid = yardstick->measure(align::to_canonical(*mesh, canonical.frame));
      fmt::print("  {:>8} {:>6} B  to scan mean {:.4f} p95 {:.4f} max {:.3f}  mask mean {:.4f} cov {:.1f} %"
                 "  parse {:.2f} ms, mesh {:.2f} ms ({} v)\n",
                 label, bytes.size(), fid->to_scan.mean, fid->to_scan.p95, fid->to_scan.max,
                 fid->coverage.distance.mean, 100 * fid->coverage.share,
                 std::chrono::duration<double, std::milli>(m - s).count(),
                 std::chrono::duration<double, std::milli>(e - m).count(), mesh->vertex_count());
      if (std::getenv("RD_WORST") != nullptr) { // where the farthest points are
        const Mesh c = align::to_canonical(*mesh, canonical.frame);
        std::vector<std::pair<double, std::size_t>> d;
        for (std::size_t v = 0; v < c.vertex_count(); v += 3)
          d.emplace_back(yardstick->distance_to_scan(c.positions[v]), v);
        std::partial_sort(d.begin(), d.begin() + 5, d.end(), std::greater<>());
        for (int i = 0; i < 5; ++i) {
          const std::size_t v = d[i].second, w = f->residual ? f->residual->field.width : 1;
          const std::size_t node = v;
          fmt::print("    worst {:.3f} at ({:.1f}, {:.1f}, {:.1f}) node ({}, {}) found {}\n", d[i].first,
                     c.positions[v].x(), c.positions[v].y(), c.positions[v].z(), node % w, node / w,
                     f->residual && node < measured.found.size() ? int(measured.found[node]) : -1);
        }
      }
    };
    report("curves", curves);
    for (const std::size_t budget : budgets) {
      Result<std::string> file = pdef::with_residual(curves, *coded, budget);
      if (!file) {
        fmt::print("  {}: {}\n", budget, file.error().to_string());
        continue;
      }
      report(std::to_string(budget), *file);
    }
  }
}

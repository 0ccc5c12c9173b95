// Decoding a face: a .pdef file (facefuns_f18 at 10 %) to a mesh of 316 x 316 = 99,856 vertices with
// normals in the scan's frame, beside libdraco decoding the same scan at 11 bits (level 7, as
// `draco_encoder -qp 11 -cl 7`), in the same run.
//
//   build/benchmarks/pdef_bench      (PDEFACE_DATA=/path/to/faces; the built-in sample face without it)
//
// Setup (alignment, slicing, encoding) is outside the timed loops. Memory is the default allocator's:
// after the first iteration freed memory is reused (docs/pde.md measures the fresh-memory case).

#include "pdeface/compare/encode.hpp"
#include "pdeface/core/sample_face.hpp"
#include "pdeface/draco/draco.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface/pdef/mesh.hpp"
#include "pdeface/pdef/pdef.hpp"

#include "bench_support.hpp"

#include <benchmark/benchmark.h>
#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>

#include <cstdio>

namespace {

using namespace pdeface;

struct Corpus {
  std::string origin;
  std::string lossy, lossless; // .pdef at 10 %
  std::string draco;           // the scan at 11 bits
  std::size_t scan_vertices = 0;
};

const Corpus& corpus() {
  static const Corpus c = [] {
    Corpus out;
    Mesh scan;
    if (auto loaded = formats::read_mesh(bench::face("facefuns_f18.ply"))) {
      scan = std::move(loaded->mesh);
      out.origin = "facefuns_f18.ply";
    } else {
      std::fprintf(stderr, "pdef_bench: facefuns_f18.ply not found; measuring the built-in sample face\n");
      scan = sample_face();
      out.origin = "sample face";
    }
    out.scan_vertices = scan.vertex_count();
    compare::EncodeRequest request;
    request.source = out.origin;
    out.lossy = compare::encode_request(scan, request).value().encoded.bytes;
    request.encoding.lossless = true;
    out.lossless = compare::encode_request(scan, request).value().encoded.bytes;
    out.draco = pdeface::draco::write(scan, {.position_bits = 11, .level = 7}).value();
    std::fprintf(
        stderr, "pdef_bench: %s (%zu vertices): .pdef %zu bytes lossy, %zu lossless; Draco %zu bytes\n",
        out.origin.c_str(), out.scan_vertices, out.lossy.size(), out.lossless.size(), out.draco.size());
    return out;
  }();
  return c;
}

// .pdef bytes to a mesh of 316 x 316 vertices with normals in the scan's frame: decode, solve, evaluate,
// triangulate, map back.
void pdef_to_mesh(benchmark::State& state, bool lossless) {
  const std::string& bytes = lossless ? corpus().lossless : corpus().lossy;
  std::size_t vertices = 0;
  for (auto _ : state) {
    const Result<pdef::Face> face = pdef::decode(bytes, "face.pdef");
    if (!face) return state.SkipWithError(face.error().to_string().c_str());
    Result<Mesh> mesh = pdef::to_mesh(*face, pdef::Resolution{316, 316});
    if (!mesh) return state.SkipWithError(mesh.error().to_string().c_str());
    vertices = mesh->vertex_count();
    benchmark::DoNotOptimize(mesh);
  }
  state.counters["file_bytes"] = static_cast<double>(bytes.size());
  state.counters["vertices"] = static_cast<double>(vertices);
}

// The bytes to the document only (no surface).
void pdef_decode(benchmark::State& state) {
  const std::string& bytes = corpus().lossy;
  for (auto _ : state) {
    Result<pdef::Face> face = pdef::decode(bytes, "face.pdef");
    if (!face) return state.SkipWithError(face.error().to_string().c_str());
    benchmark::DoNotOptimize(face);
  }
  state.counters["file_bytes"] = static_cast<double>(bytes.size());
}

// libdraco alone: the buffer to its own mesh (positions, normals).
void libdraco_decode(benchmark::State& state) {
  const std::string& bytes = corpus().draco;
  std::size_t vertices = 0;
  for (auto _ : state) {
    ::draco::DecoderBuffer buffer;
    buffer.Init(bytes.data(), bytes.size());
    ::draco::Decoder decoder;
    auto mesh = decoder.DecodeMeshFromBuffer(&buffer);
    if (!mesh.ok()) return state.SkipWithError(mesh.status().error_msg());
    vertices = mesh.value()->num_points();
    benchmark::DoNotOptimize(mesh);
  }
  state.counters["file_bytes"] = static_cast<double>(bytes.size());
  state.counters["vertices"] = static_cast<double>(vertices);
}

// Our Draco reader: the checks before libdraco, libdraco, and the conversion to a pdeface::Mesh.
void draco_to_mesh(benchmark::State& state) {
  const std::string& bytes = corpus().draco;
  std::size_t vertices = 0;
  for (auto _ : state) {
    Result<Mesh> mesh = pdeface::draco::read(bytes, "scan.drc");
    if (!mesh) return state.SkipWithError(mesh.error().to_string().c_str());
    vertices = mesh->vertex_count();
    benchmark::DoNotOptimize(mesh);
  }
  state.counters["file_bytes"] = static_cast<double>(bytes.size());
  state.counters["vertices"] = static_cast<double>(vertices);
}

} // namespace

BENCHMARK_CAPTURE(pdef_to_mesh, lossy, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(pdef_to_mesh, lossless, true)->Unit(benchmark::kMillisecond);
BENCHMARK(pdef_decode)->Unit(benchmark::kMicrosecond);
BENCHMARK(libdraco_decode)->Unit(benchmark::kMillisecond);
BENCHMARK(draco_to_mesh)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();

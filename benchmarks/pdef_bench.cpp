// Decoding a face, in one process: a .pdef file (facefuns_f18 at 10 %) to a mesh of 316 x 316 = 99,856
// vertices with normals in the scan's frame, beside libdraco decoding the same scan (30,204 vertices) at 11
// bits (level 7, as `draco_encoder -qp 11 -cl 7`), so that the ratio of the two is one run's.
//
//   build/benchmarks/pdef_bench      (PDEFACE_DATA=/path/to/faces; the built-in sample face without it)
//
// Setup (alignment, slicing, encoding) is outside the timed loops. One core, no threads. Memory is
// pinned (bench_support.hpp): "warm" reuses freed memory, as a process decoding many faces does; "fresh"
// maps every large block anew, as one command does (its page faults are counted). libdraco is measured
// both ways too. pdef_to_mesh_sse2 forces the mesher's narrowest vectors: what a processor without AVX2
// gets (the mesh is the same to the bit).

#include "pdeface/core/sample_face.hpp"
#include "pdeface/draco/draco.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface/pde/mesher.hpp"
#include "pdeface/pdef/mesh.hpp"
#include "pdeface/pdef/pdef.hpp"
#include "pdeface/pipeline/encode.hpp"

#include "bench_support.hpp"

#include <benchmark/benchmark.h>
#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>

#include <array>
#include <cstdio>
#include <map>

namespace {

using namespace pdeface;
using bench::FaultCounter;
using bench::Memory;

constexpr pdef::Resolution kGrid{316, 316};
constexpr std::array<std::size_t, 4> kResidualSizes{2048, 8192, 16384, 32768};

struct Corpus {
  std::string origin;
  std::string lossy, lossless;                 // .pdef at 10 %
  std::string draco;                           // the scan at 11 bits
  std::map<std::size_t, std::string> residual; // `pdeface encode --size`'s files (5 % curves), by size
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
    pipeline::EncodeRequest request;
    request.source = out.origin;
    out.lossy = pipeline::encode_request(scan, request).value().encoded.bytes;
    for (const std::size_t size : kResidualSizes) {
      request.residual.size_bytes = size;
      request.profiles.ratio = pipeline::default_ratio(request.residual);
      out.residual[size] = pipeline::encode_request(scan, request).value().encoded.bytes;
    }
    request.residual = {};
    request.profiles.ratio = pipeline::default_ratio(request.residual);
    request.encoding.lossless = true;
    out.lossless = pipeline::encode_request(scan, request).value().encoded.bytes;
    out.draco = pdeface::drc::write(scan, {.position_bits = 11, .level = 7}).value();
    std::fprintf(
        stderr, "pdef_bench: %s (%zu vertices): .pdef %zu bytes lossy, %zu lossless; Draco %zu bytes\n",
        out.origin.c_str(), out.scan_vertices, out.lossy.size(), out.lossless.size(), out.draco.size());
    return out;
  }();
  return c;
}

// The corpus made (with the allocator as it is), then the allocator pinned for the timed loop.
const Corpus& corpus_with(Memory memory) {
  const Corpus& c = corpus();
  bench::pin_allocator(memory);
  return c;
}

// .pdef bytes to a mesh of 316 x 316 vertices with normals in the scan's frame: decode, solve, mesh (the
// frame folded in), as `pdef::to_mesh` does; `lanes` limits the mesher's vectors (0: the widest).
Result<Mesh> pdef_mesh(const std::string& bytes, std::size_t lanes) {
  const Result<pdef::Face> face = pdef::decode(bytes, "face.pdef");
  if (!face) return face.error();
  if (lanes == 0) return pdef::to_mesh(*face, kGrid);
  const Result<pde::Surface> surface = pdef::surface_of(*face);
  if (!surface) return surface.error();
  return pde::GridMesher(*surface, kGrid.u, kGrid.v, {.map = pdef::scan_map(face->frame), .max_lanes = lanes})
      .mesh(face->frame.scan_units);
}

void pdef_to_mesh(benchmark::State& state, bool lossless, Memory memory, std::size_t lanes) {
  const std::string& bytes = lossless ? corpus_with(memory).lossless : corpus_with(memory).lossy;
  std::size_t vertices = 0;
  {
    const FaultCounter faults(state);
    for (auto _ : state) {
      Result<Mesh> mesh = pdef_mesh(bytes, lanes);
      if (!mesh) return state.SkipWithError(mesh.error().to_string().c_str());
      vertices = mesh->vertex_count();
      benchmark::DoNotOptimize(mesh);
    }
  }
  state.counters["file_bytes"] = static_cast<double>(bytes.size());
  state.counters["vertices"] = static_cast<double>(vertices);
}

// A .pdef with a residual layer of `size` bytes to the same 316 x 316 mesh (warm): what the layer adds to
// pdef_to_mesh/lossy_warm is its stream decoded, the wavelet inverted, resampled onto the grid, every
// vertex moved along its normal and the normals made again.
void pdef_residual_to_mesh(benchmark::State& state) {
  const std::string& bytes =
      corpus_with(Memory::Reused).residual.at(static_cast<std::size_t>(state.range(0)));
  std::size_t vertices = 0;
  for (auto _ : state) {
    Result<Mesh> mesh = pdef_mesh(bytes, 0);
    if (!mesh) return state.SkipWithError(mesh.error().to_string().c_str());
    vertices = mesh->vertex_count();
    benchmark::DoNotOptimize(mesh);
  }
  state.counters["file_bytes"] = static_cast<double>(bytes.size());
  state.counters["vertices"] = static_cast<double>(vertices);
}

// The residual layer's bytes to its offsets only (`pdef::decode` of the file less that of the curves).
void pdef_residual_decode(benchmark::State& state) {
  const std::string& bytes =
      corpus_with(Memory::Reused).residual.at(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    Result<pdef::Face> face = pdef::decode(bytes, "face.pdef");
    if (!face) return state.SkipWithError(face.error().to_string().c_str());
    benchmark::DoNotOptimize(face);
  }
  state.counters["file_bytes"] = static_cast<double>(bytes.size());
}

// The bytes to the document only (no surface).
void pdef_decode(benchmark::State& state) {
  const std::string& bytes = corpus_with(Memory::Reused).lossy;
  for (auto _ : state) {
    Result<pdef::Face> face = pdef::decode(bytes, "face.pdef");
    if (!face) return state.SkipWithError(face.error().to_string().c_str());
    benchmark::DoNotOptimize(face);
  }
  state.counters["file_bytes"] = static_cast<double>(bytes.size());
}

// libdraco alone: the buffer to its own mesh.
void libdraco_decode(benchmark::State& state, Memory memory) {
  const std::string& bytes = corpus_with(memory).draco;
  std::size_t vertices = 0;
  {
    const FaultCounter faults(state);
    for (auto _ : state) {
      draco::DecoderBuffer buffer;
      buffer.Init(bytes.data(), bytes.size());
      draco::Decoder decoder;
      auto mesh = decoder.DecodeMeshFromBuffer(&buffer);
      if (!mesh.ok()) return state.SkipWithError(mesh.status().error_msg());
      vertices = mesh.value()->num_points();
      benchmark::DoNotOptimize(mesh);
    }
  }
  state.counters["file_bytes"] = static_cast<double>(bytes.size());
  state.counters["vertices"] = static_cast<double>(vertices);
}

// Our Draco reader: the checks before libdraco, libdraco, and the conversion to a pdeface::Mesh.
void draco_to_mesh(benchmark::State& state) {
  const std::string& bytes = corpus_with(Memory::Reused).draco;
  std::size_t vertices = 0;
  for (auto _ : state) {
    Result<Mesh> mesh = pdeface::drc::read(bytes, "scan.drc");
    if (!mesh) return state.SkipWithError(mesh.error().to_string().c_str());
    vertices = mesh->vertex_count();
    benchmark::DoNotOptimize(mesh);
  }
  state.counters["file_bytes"] = static_cast<double>(bytes.size());
  state.counters["vertices"] = static_cast<double>(vertices);
}

// A layer with a trim meshed on its own grid (what `pdeface decode` gives), with the trim and with it
// cleared: what leaving the trimmed cells out costs (ict_03, whose eye holes, nostrils and mouth are 4 % of
// its cells; skipped without the shared scans).
const std::map<std::size_t, pdef::Face>& trimmed_faces() {
  static const std::map<std::size_t, pdef::Face> faces = [] {
    std::map<std::size_t, pdef::Face> out;
    Result<formats::LoadedMesh> scan = formats::read_mesh(bench::face("ict_03.wrl"));
    if (!scan) return out;
    pipeline::EncodeRequest request;
    request.check.reset();
    for (const std::size_t size : {std::size_t{2048}, std::size_t{16384}}) {
      request.residual.size_bytes = size;
      request.profiles.ratio = pipeline::default_ratio(request.residual);
      out[size] = pdef::decode(pipeline::encode_request(scan->mesh, request).value().encoded.bytes).value();
    }
    return out;
  }();
  return faces;
}

void pdef_trimmed_to_mesh(benchmark::State& state, bool trim) {
  const auto found = trimmed_faces().find(static_cast<std::size_t>(state.range(0)));
  if (found == trimmed_faces().end()) return state.SkipWithError("ict_03.wrl not found");
  pdef::Face face = found->second;
  if (!trim) face.residual->trimmed.clear();
  std::size_t vertices = 0;
  for (auto _ : state) {
    Result<Mesh> mesh = pdef::to_mesh(face);
    if (!mesh) return state.SkipWithError(mesh.error().to_string().c_str());
    vertices = mesh->vertex_count();
    benchmark::DoNotOptimize(mesh);
  }
  state.counters["vertices"] = static_cast<double>(vertices);
}

} // namespace

BENCHMARK_CAPTURE(pdef_to_mesh, lossy_warm, false, Memory::Reused, 0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(libdraco_decode, warm, Memory::Reused)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(pdef_to_mesh, lossy_fresh, false, Memory::Fresh, 0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(libdraco_decode, fresh, Memory::Fresh)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(pdef_to_mesh, lossless_warm, true, Memory::Reused, 0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(pdef_to_mesh, lossy_warm_sse2, false, Memory::Reused, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(pdef_decode)->Unit(benchmark::kMicrosecond);
BENCHMARK(pdef_residual_to_mesh)->Arg(2048)->Arg(8192)->Arg(16384)->Arg(32768)->Unit(benchmark::kMillisecond);
BENCHMARK(pdef_residual_decode)->Arg(2048)->Arg(8192)->Arg(16384)->Arg(32768)->Unit(benchmark::kMillisecond);
BENCHMARK(draco_to_mesh)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(pdef_trimmed_to_mesh, trimmed, true)->Arg(2048)->Arg(16384)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(pdef_trimmed_to_mesh, untrimmed, false)
    ->Arg(2048)
    ->Arg(16384)
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();

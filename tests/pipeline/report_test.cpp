// pdeface compare's library side: every variant of a scan measured on its decoded bytes, and the report's
// documents. Heavy paths run on the sample face and on one real scan (facefuns_f18) only.

#include "pdeface/align/frame.hpp"
#include "pdeface/core/sample_face.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface/pdef/mesh.hpp"
#include "pdeface/pdef/pdef.hpp"
#include "pdeface/pipeline/encode.hpp"
#include "pdeface/pipeline/reconstruct.hpp"
#include "pdeface/pipeline/report.hpp"

#include "gltf_validator.hpp"
#include "pdeface_test.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace pdeface::pipeline {
namespace {

namespace fs = std::filesystem;

// The sample face with every kind of variant, fewer of each than the defaults.
CompareOptions sample_options() {
  CompareOptions o;
  o.draco_bits = {8, 11, 14};
  o.budgets = {2048, 4096};
  o.ratios = {0.1};
  o.pde_budgets = {2048};
  o.textures = {{1.0, 80}};
  o.keep_bytes = true;
  return o;
}

// Computed once per process: the CompareSample suite runs in one process (tests/CMakeLists.txt).
const Report& sample_report() {
  static const Report r = compare_scans({.inputs = {}, .options = sample_options(), .progress = {}});
  return r;
}

const Variant* find(const ScanReport& s, std::string_view name) {
  const auto it = std::ranges::find(s.variants, name, &Variant::name);
  return it == s.variants.end() ? nullptr : &*it;
}

using test::split;

// Writes the report's files under `dir` (making its folders) and returns them.
std::vector<OutputFile> write(const Report& report, const fs::path& dir) {
  std::vector<OutputFile> files = report_files(report, dir);
  for (const OutputFile& f : files)
    fs::create_directories(f.path.parent_path());
  EXPECT_TRUE(write_files_atomic(files));
  return files;
}

TEST(CompareSample, SampleFaceHasEveryKindOfVariantMeasured) {
  const Report& r = sample_report();
  ASSERT_EQ(r.scans.size(), 1U);
  const ScanReport& s = r.scans[0];
  ASSERT_TRUE(s.failure.empty()) << s.failure;
  EXPECT_EQ(s.name, "sample face");
  EXPECT_EQ(s.units, Units::Millimetres);
  // 4 raw + 4 gzip + 3 Draco + 2 budgets + 2 at the PDE sizes + 2 PDE + 1 PDE with a residual layer, and
  // colour (its vertex colours): Draco with them, the PDE with a texture layer.
  EXPECT_EQ(s.variants.size(), 20U);
  for (const Variant& v : s.variants) {
    SCOPED_TRACE(v.name);
    ASSERT_TRUE(v.fidelity) << v.failure;
    EXPECT_GT(v.bytes, 0U);
    EXPECT_GT(v.triangles, 0U);
    EXPECT_NEAR(v.ratio_to_ply, static_cast<double>(v.bytes) / static_cast<double>(s.ply_bytes), 1e-12);
    EXPECT_GT(v.fidelity->coverage.share, 0.5);
    EXPECT_TRUE(std::isfinite(v.fidelity->mean_profile_error));
  }
  // Raw files decode to the scan itself; gzip makes them smaller.
  for (const char* raw : {"obj", "ply", "wrl", "glb"}) {
    const Variant* plain = find(s, raw);
    const Variant* gz = find(s, std::string(raw) + ".gz");
    ASSERT_TRUE(plain && gz) << raw;
    EXPECT_EQ(plain->vertices, s.vertices);
    EXPECT_LT(plain->fidelity->coverage.distance.mean, 1e-4) << raw;
    EXPECT_DOUBLE_EQ(gz->fidelity->coverage.distance.mean, plain->fidelity->coverage.distance.mean);
    EXPECT_LT(gz->bytes, plain->bytes) << raw;
  }
  EXPECT_EQ(find(s, "ply")->bytes, s.ply_bytes);
}

TEST(CompareSample, DracoErrorsShrinkWithMoreBits) {
  const ScanReport& s = sample_report().scans[0];
  const Variant *d8 = find(s, "draco 8 bits"), *d11 = find(s, "draco 11 bits"),
                *d14 = find(s, "draco 14 bits");
  ASSERT_TRUE(d8 && d11 && d14);
  EXPECT_LT(d8->bytes, d11->bytes);
  EXPECT_LT(d11->bytes, d14->bytes);
  for (auto error : {+[](const metrics::MeshFidelity& f) { return f.coverage.distance.mean; },
                     +[](const metrics::MeshFidelity& f) { return f.to_scan.mean; },
                     +[](const metrics::MeshFidelity& f) { return f.to_scan.max; }}) {
    EXPECT_GT(error(*d8->fidelity), error(*d11->fidelity));
    EXPECT_GT(error(*d11->fidelity), error(*d14->fidelity));
  }
  // Half a quantisation step per axis at most: the sample is ~230 mm across.
  EXPECT_LT(d8->fidelity->to_scan.max, 0.5 * std::sqrt(3.0) * 240.0 / 255.0);
}

TEST(CompareSample, DecimatedRowsLandWithinTenPercentUnderTheirBudgets) {
  const ScanReport& s = sample_report().scans[0];
  std::size_t rows = 0;
  for (const Variant& v : s.variants) {
    if (v.method != Method::DecimateDraco) continue;
    ++rows;
    EXPECT_LE(v.bytes, v.budget) << v.name;
    EXPECT_GE(static_cast<double>(v.bytes), 0.9 * static_cast<double>(v.budget)) << v.name;
    EXPECT_GE(v.bits, 8) << v.name;
    EXPECT_LE(v.bits, 14) << v.name;
  }
  EXPECT_EQ(rows, 4U);
  // More bytes, more triangles and less error.
  const Variant *b2 = find(s, "decimate+draco 2048 B"), *b4 = find(s, "decimate+draco 4096 B");
  ASSERT_TRUE(b2 && b4);
  EXPECT_LT(b2->triangles, b4->triangles);
  EXPECT_GT(b2->fidelity->coverage.distance.mean, b4->fidelity->coverage.distance.mean);
}

TEST(CompareSample, BytesInTheReportAreTheSizesOfTheFilesWritten) {
  const Report& r = sample_report();
  const ScanReport& s = r.scans[0];
  test::TempDir dir;
  write(r, dir.path());
  std::size_t files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir / "files"))
    files += entry.is_regular_file() ? 1 : 0;
  EXPECT_EQ(files, s.variants.size());
  // Each variant's file, by its row: the size is the row's bytes, and the bytes decode.
  const std::string csv = read_file(dir / "report.csv").value();
  for (const Variant& v : s.variants) {
    std::string stem;
    for (char c : v.name)
      stem += std::isalnum(static_cast<unsigned char>(c)) ? c : '-';
    while (stem.find("--") != std::string::npos)
      stem.replace(stem.find("--"), 2, "-");
    const fs::path file = dir / "files" / "sample-face" / (stem + v.extension);
    ASSERT_TRUE(fs::exists(file)) << file;
    EXPECT_EQ(fs::file_size(file), v.bytes) << v.name;
    EXPECT_NE(csv.find(fmt::format("\"{}\",{},", v.name, v.bits > 0 ? fmt::format("{}", v.bits) : "")),
              std::string::npos)
        << v.name;
  }
  // Draco's row is what `pdeface convert --draco-bits 11` writes for the scan's geometry.
  Mesh geometry = sample_face();
  geometry.normals.clear();
  geometry.colors.clear();
  geometry.texcoords.clear();
  const std::string drc = formats::encode_mesh(geometry, "x.drc", {.draco_bits = 11}).value();
  EXPECT_EQ(find(s, "draco 11 bits")->bytes, drc.size());
}

// A PDE row is the `.pdef` file `pdeface encode` writes for the scan (its bytes, byte for byte), measured
// on what `pdef::decode` of those bytes meshes to: the same measures from the decoded mesh, and a lossy row
// measured apart from the lossless one.
// A row with a residual layer is the file `pdeface encode --size` writes, within its budget, and it is far
// closer to the scan than the curves alone (issue 19).
TEST(CompareSample, ResidualRowIsTheSizedFileAndBeatsTheCurves) {
  const ScanReport& s = sample_report().scans[0];
  const Variant* v = find(s, "pde 5 % + residual 2048 B"); // pipeline::kResidualRatio
  const Variant* curves = find(s, "pde 10 % lossy");
  ASSERT_TRUE(v && v->fidelity && curves && curves->fidelity) << (v ? v->failure : "missing");
  EXPECT_LE(v->bytes, 2048U);
  EXPECT_EQ(v->budget, 2048U);
  EXPECT_EQ(v->encoded[4], 3); // version 3
  const Mesh scan = sample_face();
  const EncodeOutcome file =
      encode_request(scan, {.profiles = {.ratio = kResidualRatio}, .residual = {.size_bytes = 2048}}).value();
  EXPECT_TRUE(v->encoded == file.encoded.bytes);
  EXPECT_LT(v->fidelity->to_scan.mean, 0.5 * curves->fidelity->to_scan.mean);
  EXPECT_LT(v->fidelity->to_scan.p95, 0.5 * curves->fidelity->to_scan.p95);
}

TEST(CompareSample, PdeRowsAreTheRealPdefFileMeasuredOnItsDecodedMesh) {
  const ScanReport& s = sample_report().scans[0];
  const Mesh scan = sample_face();
  const align::Alignment alignment = align::align_scan(scan, std::nullopt, s.name).value();
  const CanonicalScan canonical = canonical_scan(scan, alignment);
  const metrics::FaceYardstick yardstick =
      metrics::FaceYardstick::make(canonical.mesh, extract_profiles(canonical).value()).value();
  std::array<double, 2> to_scan_mean{};
  for (bool lossless : {false, true}) {
    const Variant* v = find(s, lossless ? "pde 10 % lossless" : "pde 10 % lossy");
    ASSERT_TRUE(v && v->fidelity) << (v ? v->failure : "missing");
    SCOPED_TRACE(v->name);
    const EncodeOutcome file =
        encode_request(scan, {.profiles = {.ratio = 0.1}, .encoding = {.lossless = lossless}}).value();
    EXPECT_EQ(v->bytes, file.encoded.bytes.size());
    EXPECT_TRUE(v->encoded == file.encoded.bytes); // (not printed: binary)
    EXPECT_TRUE(v->encoded.starts_with(pdef::kMagic));
    EXPECT_GT(v->decode_ms, 0.0);

    const Mesh decoded = pdef::to_mesh(pdef::decode(v->encoded).value()).value();
    EXPECT_EQ(v->vertices, decoded.vertex_count());
    EXPECT_EQ(v->triangles, decoded.triangle_count());
    const metrics::MeshFidelity f = yardstick.measure(align::to_canonical(decoded, canonical.frame)).value();
    EXPECT_DOUBLE_EQ(v->fidelity->coverage.distance.mean, f.coverage.distance.mean);
    EXPECT_DOUBLE_EQ(v->fidelity->to_scan.mean, f.to_scan.mean);
    EXPECT_DOUBLE_EQ(v->fidelity->to_scan.max, f.to_scan.max);
    EXPECT_DOUBLE_EQ(v->fidelity->mean_profile_error, f.mean_profile_error);
    to_scan_mean[lossless ? 1 : 0] = v->fidelity->to_scan.mean;
  }
  // The lossy file is smaller and its surface is not the lossless one's, within the default error.
  EXPECT_LT(find(s, "pde 10 % lossy")->bytes, find(s, "pde 10 % lossless")->bytes);
  EXPECT_NE(to_scan_mean[0], to_scan_mean[1]);
  EXPECT_NEAR(to_scan_mean[0], to_scan_mean[1], pdef::kDefaultMaxError);
}

TEST(CompareSample, DocumentsHoldEveryRow) {
  const Report& r = sample_report();
  const ScanReport& s = r.scans[0];
  const std::string md = report_markdown(r);
  EXPECT_NE(md.find("## Summary across scans (mean ± sd)"), std::string::npos);
  EXPECT_NE(md.find("## sample face: "), std::string::npos) << md;
  for (const Variant& v : s.variants)
    EXPECT_NE(md.find("| " + v.name + " |"), std::string::npos) << v.name;

  const auto lines = split(report_csv(r), '\n');
  ASSERT_EQ(lines.size(), 1 + s.variants.size());
  const std::size_t columns = split(lines[0], ',').size();
  EXPECT_EQ(columns, 34U);
  for (std::size_t i = 1; i < lines.size(); ++i) {
    // Names hold no commas: count the separators.
    EXPECT_EQ(static_cast<std::size_t>(std::ranges::count(lines[i], ',')), columns - 1) << lines[i];
  }

  const nlohmann::json j = nlohmann::json::parse(report_json(r));
  EXPECT_EQ(j["format"], "pdeface-compare");
  ASSERT_EQ(j["scans"].size(), 1U);
  ASSERT_EQ(j["scans"][0]["variants"].size(), s.variants.size());
  const nlohmann::json& d11 = j["scans"][0]["variants"][9];
  EXPECT_EQ(d11["name"], "draco 11 bits");
  EXPECT_EQ(d11["bytes"], find(s, "draco 11 bits")->bytes);
  EXPECT_NEAR(d11["fidelity"]["mask_to_mesh"]["mean"].get<double>(),
              find(s, "draco 11 bits")->fidelity->coverage.distance.mean, 1e-12);

  const std::string plot = rd_svg(r);
  for (const char* text : {"bytes (log scale)", "mean distance", "Draco (bits)", "decimate + Draco",
                           "PDE .pdef lossy (ratio)", "<polyline"})
    EXPECT_NE(plot.find(text), std::string::npos) << text;
  const std::string page = report_html(r);
  EXPECT_NE(page.find("<svg"), std::string::npos);
  EXPECT_NE(page.find("data:image/png;base64,"), std::string::npos); // the heat maps' pictures
  EXPECT_EQ(page.find("src=\"http"), std::string::npos);             // self-contained
}

// A variant no scan could make (a budget the whole scan fits under) says why in its scan's table, with no
// numbers, and has no row in the summary.
TEST(CompareSample, AVariantNoScanMadeSaysWhyAndHasNoSummaryRow) {
  Report r = sample_report();
  ASSERT_FALSE(r.scans.empty());
  r.scans[0].variants.push_back({.method = Method::DecimateDraco,
                                 .name = "decimate+draco 1048576 B",
                                 .budget = 1048576,
                                 .failure = "nothing to decimate"});
  const std::string md = report_markdown(r);
  const std::size_t scans = md.find("\n## ", md.find("## Summary") + 1);
  ASSERT_NE(scans, std::string::npos);
  EXPECT_EQ(md.substr(0, scans).find("decimate+draco 1048576 B"), std::string::npos) << md;
  const std::size_t row = md.find("| decimate+draco 1048576 B |", scans);
  ASSERT_NE(row, std::string::npos) << md;
  const std::string line = md.substr(row, md.find('\n', row) - row);
  EXPECT_NE(line.find("failed: nothing to decimate"), std::string::npos) << line;
  EXPECT_EQ(line.find("inf"), std::string::npos) << line;
  EXPECT_EQ(line.find("| 0 |"), std::string::npos) << line;
}

// The colour rows (issue 20): Draco with the vertex colours, and the `.pdef` with a texture layer, both
// measured on the face's colours (PSNR, ΔE₀₀) against the scan's; their bytes in parts; a textured GLB each
// that the validator passes. The texture row is the file `pdeface encode --texture` writes.
TEST(CompareSample, ColourRowsAreMeasuredAndWrittenAsTexturedGlbs) {
  const Report& r = sample_report();
  const ScanReport& s = r.scans[0];
  EXPECT_EQ(s.colour, metrics::ColourSource::VertexColours);
  const Variant* draco = find(s, "draco 11 bits + colours");
  const Variant* pde = find(s, "pde 10 % + texture 1 mm q80");
  ASSERT_TRUE(draco && pde);
  for (const Variant* v : {draco, pde}) {
    SCOPED_TRACE(v->name);
    ASSERT_TRUE(v->colour && v->fidelity) << v->failure;
    EXPECT_GT(v->colour->samples, 10'000U);
    EXPECT_EQ(v->colour->uncoloured, 0U);
    EXPECT_GT(v->colour->psnr_db, 40.0); // smooth skin tones: both close
    EXPECT_LT(v->colour->mean_delta_e, 1.0);
    EXPECT_GE(v->colour->p95_delta_e, v->colour->mean_delta_e);
  }
  // Draco's colours cost bytes over the geometry alone; the texture layer is its JPEG in the file.
  EXPECT_EQ(draco->attribute_bytes, draco->bytes - find(s, "draco 11 bits")->bytes);
  EXPECT_GT(draco->attribute_bytes, 0U);
  EXPECT_EQ(draco->image_bytes, 0U);
  const EncodeOutcome file = encode_request(sample_face(), {.profiles = {.ratio = 0.1},
                                                            .texture = {.wanted = true, .texel_mm = 1.0}})
                                 .value();
  EXPECT_TRUE(pde->encoded == file.encoded.bytes);
  EXPECT_EQ(pde->image_bytes, file.texture->bytes);
  EXPECT_LT(pde->bytes, draco->bytes);
  // The geometry rows are not measured on colour.
  EXPECT_FALSE(find(s, "draco 11 bits")->colour);
  EXPECT_FALSE(find(s, "pde 10 % lossy")->colour);
  // A textured GLB of each colour row, and the documents list the measures.
  ASSERT_EQ(s.textured.size(), 2U);
  for (const TexturedGlb& t : s.textured) {
    const Result<formats::LoadedMesh> back = formats::read_mesh(t.glb, t.file);
    ASSERT_TRUE(back) << back.error().to_string();
    EXPECT_TRUE(back->mesh.has_colors() || (back->mesh.material && back->mesh.material->base_color_image))
        << t.file;
  }
  const std::string md = report_markdown(r);
  EXPECT_NE(md.find("## Colour across scans"), std::string::npos);
  EXPECT_NE(md.find("Colour (the scan's vertex colours; face mask)"), std::string::npos);
  const nlohmann::json j = nlohmann::json::parse(report_json(r));
  EXPECT_EQ(j["scans"][0]["colour"], "vertex colours");
  EXPECT_EQ(j["scans"][0]["textured"].size(), 2U);
  PDEFACE_GLTF_VALIDATOR_OR_SKIP(node, validator);
  test::TempDir dir;
  for (const TexturedGlb& t : s.textured) {
    ASSERT_TRUE(write_file_atomic(dir / t.file, t.glb));
    test::expect_valid_gltf(*node, *validator, dir / t.file);
  }
}

// Without colour asked for (or on a scan without colour) there are no colour rows.
TEST(Compare, NoColourRowsWhenNotAskedOrWithoutColour) {
  Mesh plain = sample_face({.spacing_mm = 2.0});
  plain.colors.clear();
  CompareOptions o = sample_options();
  o.draco_bits = {11};
  o.budgets = {};
  o.budgets_at_pde = false;
  o.pde_budgets = {};
  o.pde_lossless = false;
  const ScanReport bare = compare_scan(plain, "plain", o).value();
  EXPECT_EQ(bare.colour, metrics::ColourSource::None);
  EXPECT_TRUE(bare.textured.empty());
  EXPECT_FALSE(std::ranges::any_of(bare.variants, [](const Variant& v) { return v.colour.has_value(); }));
  o.colour = false;
  const ScanReport off = compare_scan(sample_face({.spacing_mm = 2.0}), "off", o).value();
  EXPECT_EQ(off.variants.size(), bare.variants.size());
  EXPECT_TRUE(off.textured.empty());
}

TEST(CompareSample, HeatMapGlbsPassTheValidator) {
  const Report& r = sample_report();
  const ScanReport& s = r.scans[0];
  ASSERT_EQ(s.heat_maps.size(), 3U); // Draco 11 bits, decimate + Draco at the PDE's size, the PDE at 10 %
  test::TempDir dir;
  for (const HeatMap& h : s.heat_maps) {
    SCOPED_TRACE(h.file);
    const Result<formats::LoadedMesh> back = formats::read_mesh(h.glb, h.file);
    ASSERT_TRUE(back) << back.error().to_string();
    EXPECT_TRUE(back->mesh.has_colors());
    // Colours vary (the error is not the same everywhere).
    const auto [lo, hi] =
        std::ranges::minmax_element(back->mesh.colors, {}, [](const Vec4f& c) { return c[0]; });
    EXPECT_LT((*lo)[0], (*hi)[0]);
  }
  PDEFACE_GLTF_VALIDATOR_OR_SKIP(node, validator);
  for (const OutputFile& f : write(r, dir.path()))
    if (f.path.extension() == ".glb") {
      SCOPED_TRACE(f.path.string());
      test::expect_valid_gltf(*node, *validator, f.path);
    }
}

TEST(Compare, UnreadableAndFacelessScansAreReportedAndTheOthersGoOn) {
  test::TempDir dir;
  ASSERT_TRUE(formats::write_mesh(sample_face(), dir / "face.ply"));
  ASSERT_TRUE(
      write_file_atomic(dir / "broken.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 9\n"));
  Mesh flat; // a plane: no face
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j)
      flat.positions.emplace_back(10.0 * i, 10.0 * j, 0.0);
  for (std::uint32_t i = 0; i < 19; ++i)
    for (std::uint32_t j = 0; j < 19; ++j) {
      flat.triangles.push_back({20 * i + j, 20 * (i + 1) + j, 20 * i + j + 1});
      flat.triangles.push_back({20 * (i + 1) + j, 20 * (i + 1) + j + 1, 20 * i + j + 1});
    }
  ASSERT_TRUE(formats::write_mesh(flat, dir / "plane.obj"));
  const auto inputs = expand_inputs(std::vector<fs::path>{dir.path()}).value();
  ASSERT_EQ(inputs.size(), 3U);
  EXPECT_EQ(inputs[0].filename(), "broken.ply"); // sorted
  CompareOptions o;
  o.draco_bits = {11};
  o.budgets = {2048};
  o.ratios = {0.1};
  o.pde_lossless = false;
  o.decimate_bits = {11};
  o.budgets_at_pde = false;
  o.pde_budgets = {}; // the failures are what this test is about: one of each kind of variant is enough
  std::vector<Progress> seen;
  const Report r = compare_scans(
      {.inputs = inputs, .options = o, .progress = [&](const Progress& p) { seen.push_back(p); }});
  ASSERT_EQ(r.scans.size(), 3U);
  EXPECT_EQ(r.failed(), 2U);
  EXPECT_NE(r.scans[0].failure.find("broken.ply"), std::string::npos) << r.scans[0].failure;
  EXPECT_TRUE(r.scans[1].failure.empty()) << r.scans[1].failure;
  EXPECT_FALSE(r.scans[1].variants.empty());
  EXPECT_NE(r.scans[2].failure.find("plane.obj"), std::string::npos) << r.scans[2].failure;
  ASSERT_FALSE(seen.empty());
  EXPECT_EQ(seen.back().scans_done, 3U);
  EXPECT_EQ(seen.back().scans_failed, 2U);
  EXPECT_EQ(seen.back().steps_done, seen.back().steps_total);
  for (std::size_t i = 1; i < seen.size(); ++i)
    EXPECT_GE(seen[i].steps_done, seen[i - 1].steps_done);
  // Typed events: a failure carries its error as a field, never to be cut out of a sentence.
  std::size_t failures = 0, done = 0;
  for (const Progress& p : seen) {
    if (p.event == ProgressEvent::Failed) {
      ++failures;
      EXPECT_FALSE(p.failure.empty());
      EXPECT_EQ(p.what(), "failed: " + p.failure);
    }
    if (p.event == ProgressEvent::Done) {
      ++done;
      EXPECT_EQ(p.scan, "face.ply");
      EXPECT_TRUE(p.what().starts_with("done in ")) << p.what();
    }
  }
  EXPECT_EQ(failures, 2U);
  EXPECT_EQ(done, 1U);
  const std::string md = report_markdown(r);
  EXPECT_NE(md.find("## broken.ply: failed"), std::string::npos) << md;
  EXPECT_NE(md.find("3 scans (2 failed)"), std::string::npos) << md;

  EXPECT_FALSE(expand_inputs(std::vector<fs::path>{dir / "absent"}));
}

// The figures on a real scan: Draco at 11 bits is what draco_encoder gives (58,211 bytes for
// facefuns_f18, -qp 11 -cl 7), and decimate + Draco within 20 % of the reference figures (meshoptimizer
// through gltfpack, best quantisation per budget: 1 KB 665–807 triangles, mask → mesh 0.43–0.49 mm;
// 2 KB 1.3–1.4k, 0.25–0.29 mm; 4 KB 3.0–3.3k, 0.16 mm).
TEST(Compare, RealScanMatchesTheReferenceFigures) {
  PDEFACE_FACE_OR_SKIP(path, "facefuns_f18.ply");
  CompareOptions o;
  o.draco_bits = {11};
  o.budgets = {1024, 2048, 4096};
  o.ratios = {};
  const Report r = compare_scans({.inputs = {path}, .options = o, .progress = {}});
  ASSERT_EQ(r.failed(), 0U) << r.scans[0].failure;
  const ScanReport& s = r.scans[0];
  const Variant* d11 = find(s, "draco 11 bits");
  ASSERT_TRUE(d11 && d11->fidelity);
  EXPECT_GE(d11->bytes, 55'000U);
  EXPECT_LE(d11->bytes, 60'000U);
  struct Reference {
    const char* name;
    double triangles_lo, triangles_hi, mean_lo, mean_hi;
  };
  for (const Reference& ref : {Reference{"decimate+draco 1024 B", 665, 807, 0.43, 0.49},
                               Reference{"decimate+draco 2048 B", 1300, 1400, 0.25, 0.29},
                               Reference{"decimate+draco 4096 B", 3000, 3300, 0.16, 0.16}}) {
    SCOPED_TRACE(ref.name);
    const Variant* v = find(s, ref.name);
    ASSERT_TRUE(v && v->fidelity) << (v ? v->failure : "missing");
    EXPECT_LE(v->bytes, v->budget);
    EXPECT_GE(static_cast<double>(v->bytes), 0.9 * static_cast<double>(v->budget));
    EXPECT_GE(static_cast<double>(v->triangles), 0.8 * ref.triangles_lo);
    EXPECT_LE(static_cast<double>(v->triangles), 1.2 * ref.triangles_hi);
    EXPECT_GE(v->fidelity->coverage.distance.mean, 0.8 * ref.mean_lo);
    EXPECT_LE(v->fidelity->coverage.distance.mean, 1.2 * ref.mean_hi);
  }
}

} // namespace
} // namespace pdeface::pipeline

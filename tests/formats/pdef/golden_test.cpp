// Golden files in tests/data/pdef: made once (DISABLED_Regenerate, run on purpose), then every change to
// the format or the encoder that alters their bytes or what they decode to fails here.
//   tiny.pdef                     synthetic_face(4, 4), lossy: the worked example of docs/pdef-format.md
//   synthetic.pdef / _lossless    synthetic_face(), lossy and lossless, with landmarks and a name
//   sample_10.pdef / _lossless    the built-in sample face through the whole pipeline at 10 %
//   (sample_10.json:
//                                 what it held when it was made)
//   sample_residual.pdef          version 3, with a residual layer and a trim (made and described in
//                                 residual_test.cpp); here only the independent reader's test reads it
//   sample_residual_offsets.pdef  the same made by the first version 3 writer: offsets alone (kind 1)

#include "pdeface/core/sample_face.hpp"
#include "pdeface/pdef/mesh.hpp"
#include "pdeface/pdef/pdef.hpp"
#include "pdeface/pipeline/encode.hpp"

#include "pdef_support.hpp"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace pdeface::pdef {
namespace {

using test::slurp;
using test::synthetic_face;

std::filesystem::path golden(std::string_view name) { return test::fixtures() / "pdef" / name; }

Face landmarked(Face face) {
  face.name = "synthetic face";
  face.landmarks = {{"nose_tip", Vec3(0.125, 0.25, 18.0)}, {"chin", Vec3(0.0, -68.0, 2.5)}};
  return face;
}

pipeline::EncodeRequest sample_request(bool lossless) {
  pipeline::EncodeRequest r;
  r.encoding.lossless = lossless;
  r.source = "sample face";
  return r;
}

TEST(PdefGolden, DISABLED_Regenerate) {
  std::filesystem::create_directories(golden(""));
  const auto write = [](std::string_view name, const std::string& bytes) {
    std::ofstream(golden(name), std::ios::binary) << bytes;
  };
  write("tiny.pdef", encode(synthetic_face(4, 4)).value().bytes);
  write("synthetic.pdef", encode(landmarked(synthetic_face())).value().bytes);
  write("synthetic_lossless.pdef", encode(landmarked(synthetic_face()), {.lossless = true}).value().bytes);
  const Mesh sample = sample_face();
  const pipeline::EncodeOutcome lossy = pipeline::encode_request(sample, sample_request(false)).value();
  const pipeline::EncodeOutcome lossless = pipeline::encode_request(sample, sample_request(true)).value();
  write("sample_10.pdef", lossy.encoded.bytes);
  write("sample_10_lossless.pdef", lossless.encoded.bytes);
  nlohmann::json j;
  j["made_by"] =
      "tests/formats/pdef/golden_test.cpp (PdefGolden.DISABLED_Regenerate) from pdeface::sample_face()";
  j["curves"] = lossless.face.curve_count();
  j["samples"] = lossless.face.sample_count();
  j["modes"] = *lossless.face.pde.modes;
  j["smoothing"] = *lossless.face.pde.smoothing;
  j["planes_mm"] = lossless.face.planes;
  j["lossy_bytes"] = lossy.encoded.bytes.size();
  j["lossy_step_mm"] = lossy.encoded.step_mm;
  j["lossless_bytes"] = lossless.encoded.bytes.size();
  std::ofstream(golden("sample_10.json")) << j.dump(2) << "\n";
}

TEST(PdefGolden, TheEncoderWritesTheGoldenBytes) {
  EXPECT_EQ(encode(synthetic_face(4, 4)).value().bytes, slurp(golden("tiny.pdef")));
  EXPECT_EQ(encode(landmarked(synthetic_face())).value().bytes, slurp(golden("synthetic.pdef")));
  EXPECT_EQ(encode(landmarked(synthetic_face()), {.lossless = true}).value().bytes,
            slurp(golden("synthetic_lossless.pdef")));
  // Files from the pipeline: the slicer may change, so their faces are encoded again as decoded.
  for (const char* name : {"sample_10.pdef", "sample_10_lossless.pdef"}) {
    const std::string bytes = slurp(golden(name));
    const Face face = decode(bytes, name).value();
    EXPECT_EQ(encode(face, {.lossless = face.storage.lossless}).value().bytes, bytes) << name;
  }
}

// Every decoded value of a file made from synthetic_face: on the file's grid, the formula's value rounded to
// it (z, and y when predicted or at a curve's ends; a height's y within half a step of it), within the
// maximum error, x on its curve's plane.
void expect_synthetic_values(const Face& decoded, const Face& formula) {
  ASSERT_EQ(decoded.curve_count(), formula.curve_count());
  ASSERT_EQ(decoded.sample_count(), formula.sample_count());
  const double step = decoded.storage.step_mm, plane_step = decoded.storage.plane_step_mm;
  ASSERT_GT(step, 0);
  for (std::size_t j = 0; j < formula.curve_count(); ++j) {
    EXPECT_EQ(decoded.planes[j], std::round(formula.planes[j] / plane_step) * plane_step) << j;
    for (Eigen::Index k = 0; k < formula.curves.samples[j].rows(); ++k) {
      const auto& want = formula.curves.samples[j];
      const auto& got = decoded.curves.samples[j];
      EXPECT_EQ(got(k, 0), decoded.planes[j]);
      const bool end = k == 0 || k + 1 == formula.curves.samples[j].rows();
      if (decoded.storage.heights_stride == 0 || end) // predicted, or a curve's extent: on the grid
        EXPECT_EQ(got(k, 1), std::round(want(k, 1) / step) * step) << j << "," << k;
      else // a height plus its residual on the grid
        EXPECT_LE(std::abs(got(k, 1) - want(k, 1)), step / 2) << j << "," << k;
      EXPECT_EQ(got(k, 2), std::round(want(k, 2) / step) * step) << j << "," << k;
      EXPECT_LE((got.row(k) - want.row(k)).norm(), kDefaultMaxError) << j << "," << k;
    }
  }
  EXPECT_EQ(decoded.filled, formula.filled);
  EXPECT_EQ(decoded.pde.smoothing, formula.pde.smoothing);
  EXPECT_EQ(decoded.pde.modes, formula.pde.modes);
  EXPECT_EQ(decoded.frame.scan_units, Units::Centimetres);
  EXPECT_NEAR(decoded.frame.translation.z(), 300.25, 1e-4);
}

TEST(PdefGolden, SyntheticFilesDecodeToTheFormulasValues) {
  const Result<Face> tiny = decode(slurp(golden("tiny.pdef")), "tiny.pdef");
  ASSERT_TRUE(tiny) << tiny.error().to_string();
  expect_synthetic_values(*tiny, synthetic_face(4, 4));

  const Face formula = landmarked(synthetic_face());
  const Result<Face> lossy = decode(slurp(golden("synthetic.pdef")), "synthetic.pdef");
  ASSERT_TRUE(lossy) << lossy.error().to_string();
  expect_synthetic_values(*lossy, formula);
  EXPECT_EQ(lossy->name, "synthetic face");
  ASSERT_EQ(lossy->landmarks.size(), 2U);
  EXPECT_EQ(lossy->landmarks[0].name, "nose_tip");
  // 0.125, 0.25, 18 and the rest: on the grid as rounded
  for (int i = 0; i < 3; ++i)
    EXPECT_EQ(lossy->landmarks[1].position(i),
              std::round(formula.landmarks[1].position(i) / lossy->storage.step_mm) * lossy->storage.step_mm);

  const Result<Face> exact = decode(slurp(golden("synthetic_lossless.pdef")), "synthetic_lossless.pdef");
  ASSERT_TRUE(exact) << exact.error().to_string();
  for (std::size_t j = 0; j < formula.curve_count(); ++j)
    EXPECT_TRUE(exact->curves.samples[j] == formula.curves.samples[j]) << j;
  EXPECT_EQ(exact->planes, formula.planes);
  EXPECT_TRUE(exact->frame.rotation == formula.frame.rotation);
  EXPECT_TRUE(exact->landmarks[0].position == formula.landmarks[0].position);
}

TEST(PdefGolden, SampleFilesDecodeToWhatTheyHeld) {
  const nlohmann::json j = nlohmann::json::parse(slurp(golden("sample_10.json")));
  const std::string lossy_bytes = slurp(golden("sample_10.pdef")),
                    exact_bytes = slurp(golden("sample_10_lossless.pdef"));
  EXPECT_EQ(lossy_bytes.size(), j["lossy_bytes"].get<std::size_t>());
  EXPECT_EQ(exact_bytes.size(), j["lossless_bytes"].get<std::size_t>());
  const Result<Face> lossy = decode(lossy_bytes, "sample_10.pdef"),
                     exact = decode(exact_bytes, "sample_10_lossless.pdef");
  ASSERT_TRUE(lossy && exact);
  for (const Face* f : {&*lossy, &*exact}) {
    EXPECT_EQ(f->curve_count(), j["curves"].get<std::size_t>());
    EXPECT_EQ(f->sample_count(), j["samples"].get<std::size_t>());
    EXPECT_EQ(*f->pde.modes, j["modes"].get<std::size_t>());
    EXPECT_EQ(*f->pde.smoothing, j["smoothing"].get<double>());
    EXPECT_EQ(f->pde.spacing, pde::Spacing::Physical);
    EXPECT_EQ(f->frame.scan_units, Units::Millimetres);
  }
  EXPECT_EQ(exact->planes, j["planes_mm"].get<std::vector<double>>());
  EXPECT_EQ(lossy->storage.step_mm, j["lossy_step_mm"].get<double>());
  // The lossy file against the exact one: every sample within the maximum error, and the surfaces too.
  for (std::size_t c = 0; c < exact->curve_count(); ++c)
    EXPECT_LE((lossy->curves.samples[c] - exact->curves.samples[c]).rowwise().norm().maxCoeff(),
              kDefaultMaxError)
        << c;
  EXPECT_EQ(lossy->filled, exact->filled);
  std::size_t filled = 0;
  for (const std::vector<bool>& curve : exact->filled)
    filled += static_cast<std::size_t>(std::ranges::count(curve, true));
  EXPECT_GT(filled, 0U); // the sample face has holes: the curves record where they were filled
}

// tests/tools/pdef_reader.py, a reader written from docs/pdef-format.md alone (Python, no code shared),
// run on a file: its output ("" when it failed).
std::string independent_reading(const std::filesystem::path& file, const std::filesystem::path& out) {
  const std::string cmd = "python3 '" +
                          (std::filesystem::path(PDEFACE_TEST_TOOLS) / "pdef_reader.py").string() + "' '" +
                          file.string() + "' > '" + out.string() + "'";
  if (std::system(cmd.c_str()) != 0) return {};
  return slurp(out);
}

// The reader's document and samples ("j k x y z filled", after two lines of settings) against `face`, bit
// for bit; leaves `in` at the first line that is not a sample.
void expect_same_samples(std::istream& in, const Face& face, std::string_view name) {
  std::string header, steps;
  std::getline(in, header);
  std::getline(in, steps);
  EXPECT_NE(
      header.find(fmt::format("J {} K {} N {}", face.curve_count(), face.sample_count(), *face.pde.modes)),
      std::string::npos)
      << header;
  std::size_t lines = 0;
  for (std::size_t j = 0, k = 0; in >> j >> k; ++lines) {
    double x = 0, y = 0, z = 0;
    int filled = 0;
    in >> x >> y >> z >> filled;
    ASSERT_LT(j, face.curve_count());
    ASSERT_LT(k, face.sample_count());
    const auto row = static_cast<Eigen::Index>(k);
    EXPECT_EQ(x, face.curves.samples[j](row, 0)) << name << " " << j << "," << k;
    EXPECT_EQ(y, face.curves.samples[j](row, 1)) << name << " " << j << "," << k;
    EXPECT_EQ(z, face.curves.samples[j](row, 2)) << name << " " << j << "," << k;
    EXPECT_EQ(filled != 0, face.filled[j][k]) << name << " " << j << "," << k;
  }
  EXPECT_EQ(lines, face.curve_count() * face.sample_count()) << name;
  in.clear();
}

// The independent reader decodes the lossy golden files to the same values, bit for bit.
TEST(PdefSpec, AnIndependentReaderAgrees) {
  if (std::system("python3 --version >/dev/null 2>&1") != 0) GTEST_SKIP() << "python3 not found";
  const test::TempDir tmp;
  for (const char* name : {"tiny.pdef", "synthetic.pdef", "sample_10.pdef"}) {
    const std::string text = independent_reading(golden(name), tmp / "values.txt");
    ASSERT_FALSE(text.empty()) << name;
    std::istringstream in(text);
    expect_same_samples(in, decode(slurp(golden(name)), name).value(), name);
    std::string rest;
    EXPECT_FALSE(std::getline(in, rest)) << name << ": " << rest; // a version 2 file: nothing after
  }
}

// The reader's residual layer ("residual none: ..." when cut inside the layer's header, else a line of
// settings and H rows of W offsets) against the C++ decoder's, the offsets bit for bit.
void expect_same_residual(std::istream& in, const Face& face, const std::string& what) {
  ASSERT_TRUE(face.residual) << what;
  const Residual& layer = *face.residual;
  std::string line;
  ASSERT_TRUE(std::getline(in, line)) << what;
  if (line.starts_with("residual none")) {
    EXPECT_TRUE(layer.field.empty()) << what;
    return;
  }
  ASSERT_FALSE(layer.field.empty()) << what << ": the reader decoded a stream, the C++ did not";
  std::istringstream settings(line);
  std::string word;
  std::size_t width = 0, height = 0, levels = 0, planes = 0, stream = 0, held = 0;
  double step = 0;
  int complete = 0;
  settings >> word >> word >> width >> word >> height >> word >> levels >> word >> step >> word >> planes >>
      word >> stream >> word >> held >> word >> complete;
  ASSERT_TRUE(settings) << what << ": " << line;
  EXPECT_EQ(width, layer.field.width) << what;
  EXPECT_EQ(height, layer.field.height) << what;
  EXPECT_EQ(levels, layer.levels) << what;
  EXPECT_EQ(step, layer.step_mm) << what;
  EXPECT_EQ(planes, layer.planes) << what;
  EXPECT_EQ(stream, layer.stream_bytes) << what;
  EXPECT_EQ(held, layer.bytes_read) << what;
  EXPECT_EQ(complete != 0, layer.complete) << what;
  ASSERT_EQ(layer.field.values.size(), width * height) << what;
  std::size_t differ = 0, n = 0;
  for (double d = 0; n < layer.field.values.size() && in >> d; ++n)
    if (d != layer.field.values[n] && differ++ < 5)
      ADD_FAILURE() << what << ": node (" << n % width << ", " << n / width << "): reader "
                    << fmt::format("{:.17g}", d) << ", C++ " << fmt::format("{:.17g}", layer.field.values[n]);
  EXPECT_EQ(n, layer.field.values.size()) << what;
  EXPECT_EQ(differ, 0U) << what << ": offsets that differ";
  // The trim: "trim bytes T held n complete 0|1 cells c", then the trimmed cells' indices.
  in.clear();
  std::string trim_line, cells_line;
  ASSERT_TRUE(std::getline(in >> std::ws, trim_line)) << what;
  std::istringstream trim(trim_line);
  std::size_t bytes = 0, trim_held = 0, count = 0;
  int trim_complete = 0;
  trim >> word >> word >> bytes >> word >> trim_held >> word >> trim_complete >> word >> count;
  ASSERT_TRUE(trim) << what << ": " << trim_line;
  EXPECT_EQ(bytes, layer.trim_bytes) << what;
  EXPECT_EQ(trim_held, layer.trim_bytes_read) << what;
  EXPECT_EQ(trim_complete != 0, layer.trim_complete) << what;
  std::getline(in, cells_line);
  std::vector<std::size_t> cells;
  std::istringstream listed(cells_line);
  for (std::size_t c = 0; listed >> c;)
    cells.push_back(c);
  EXPECT_EQ(cells.size(), count) << what;
  std::vector<std::size_t> ours;
  for (std::size_t c = 0; c < layer.trimmed.size(); ++c)
    if (layer.trimmed[c] != 0) ours.push_back(c);
  EXPECT_EQ(cells, ours) << what << ": trimmed cells that differ";
}

// The same reader decodes the residual layer of a version 3 file (the built-in sample face with a layer,
// tests/data/pdef/sample_residual.pdef) whole and cut at bytes of its layer (any prefix decodes: inside
// the header, at its end, inside the range coder's first bytes, inside the stream) to the offsets of the
// C++ decoder, bit for bit.
TEST(PdefSpec, AnIndependentReaderReadsTheResidualLayer) {
  if (std::system("python3 --version >/dev/null 2>&1") != 0) GTEST_SKIP() << "python3 not found";
  const test::TempDir tmp;
  // sample_residual.pdef has a trim (kind 2); sample_residual_offsets.pdef is the first writer's layer of
  // offsets alone (kind 1), which every reader still reads.
  for (const char* name : {"sample_residual.pdef", "sample_residual_offsets.pdef"}) {
    const std::string file = slurp(golden(name));
    const Face whole = decode(file, name).value();
    ASSERT_TRUE(whole.residual && whole.residual->complete) << name;
    const std::size_t at = whole.residual->offset, trim = at + whole.residual->header_bytes;
    const std::size_t stream = trim + whole.residual->trim_bytes;
    ASSERT_EQ(stream + whole.residual->stream_bytes, file.size()) << name;
    std::vector<std::size_t> cuts{file.size(),  at,           at + 1,       at + 7,
                                  stream,       stream + 1,   stream + 3,   stream + 4,
                                  stream + 5,   stream + 6,   stream + 10,  stream + 37,
                                  stream + 100, stream + 255, stream + 500, file.size() - 1};
    if (whole.residual->trim_bytes > 0) { // inside the trim: before its coder has 4 bytes, and later
      ASSERT_FALSE(whole.residual->trimmed.empty()) << name;
      for (const std::size_t in : {1, 3, 4, 5, 9, 17, 33})
        if (in < whole.residual->trim_bytes) cuts.push_back(trim + in);
    }
    for (const std::size_t n : cuts) {
      const std::string what = fmt::format("{} cut to {} bytes", name, n);
      const std::filesystem::path cut = tmp / "cut.pdef";
      std::ofstream(cut, std::ios::binary) << file.substr(0, n);
      const std::string text = independent_reading(cut, tmp / "values.txt");
      ASSERT_FALSE(text.empty()) << what;
      const Face face = decode(std::string_view(file).substr(0, n), "cut").value();
      std::istringstream in(text);
      expect_same_samples(in, face, what);
      expect_same_residual(in, face, what);
    }
  }
  // A prefix cut inside the header still has what it holds checked as it is read: both refuse an unknown
  // kind and a varint not in its shortest form.
  const std::string file = slurp(golden("sample_residual.pdef"));
  const std::string curves = file.substr(0, decode(file, "sample_residual.pdef").value().residual->offset);
  for (const auto& [cut, code] : {std::pair{curves + "\x03", ErrorCode::UnsupportedFormat},
                                  std::pair{curves + std::string("\x01\x80\x00", 3), ErrorCode::Malformed}}) {
    const std::filesystem::path path = tmp / "hostile.pdef";
    std::ofstream(path, std::ios::binary) << cut;
    EXPECT_EQ(independent_reading(path, tmp / "values.txt"), "") << cut.size() << " bytes";
    const Result<Face> face = decode(cut, "hostile");
    ASSERT_FALSE(face) << cut.size() << " bytes";
    EXPECT_EQ(face.error().code, code) << face.error().to_string();
  }
}

} // namespace
} // namespace pdeface::pdef

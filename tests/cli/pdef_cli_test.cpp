// .pdef on the command line: encode, decode, info and convert, with good and bad input.

#include "cli_fixture.hpp"

#include "gltf_validator.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface_test.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <fstream>

namespace pdeface::test {
namespace {

class PdefCli : public Cli {
protected:
  void SetUp() override { ASSERT_EQ(run({"sample", path("face.ply")}).exit_code, 0); }
};

// A residual layer goes on 5 % curves unless the command names the curves' points: the layer gets the bytes
// the curves do not take (pipeline::kResidualRatio).
TEST_F(PdefCli, EncodeWithALayerTakesTheFewestCurvePointsUnlessTold) {
  const auto encode = [&](std::vector<std::string> extra) {
    std::vector<std::string> args{"encode", path("face.ply"), "-o", path("sized.pdef")};
    args.insert(args.end(), extra.begin(), extra.end());
    return run(args);
  };
  for (const auto& [extra, points] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"--size", "2048"}, "28 curves x 15 points (5.0 % of 300)"},
           {{"--target-error", "0.2"}, "28 curves x 15 points (5.0 % of 300)"},
           {{"--size", "2048", "--ratio", "0.1"}, "28 curves x 30 points (10.0 % of 300)"},
           {{"--size", "2048", "--points", "20"}, "28 curves x 20 points"},
           {{}, "28 curves x 30 points (10.0 % of 300)"}}) {
    const Outcome e = encode(extra);
    ASSERT_EQ(e.exit_code, 0) << e.err;
    EXPECT_NE(e.out.find(points), std::string::npos) << e.out;
    if (!extra.empty() && extra[0] == "--size") {
      EXPECT_LE(slurp(work_ / "sized.pdef").size(), 2048U);
    }
  }
}

// `info` on a file with a residual layer says what the layer holds and that the counts are of the mesh
// `decode` makes by default: the layer's own grid, not the curves' 1 mm one.
TEST_F(PdefCli, InfoDescribesTheResidualLayer) {
  ASSERT_EQ(run({"encode", path("face.ply"), "-o", path("layer.pdef"), "--size", "4096"}).exit_code, 0);
  const Outcome i = run({"info", path("layer.pdef")});
  ASSERT_EQ(i.exit_code, 0) << i.err;
  EXPECT_NE(i.out.find("  residual        "), std::string::npos) << i.out;
  EXPECT_NE(i.out.find("bit-planes reached, the stream whole"), std::string::npos) << i.out;
  EXPECT_EQ(i.out.find("about 1 mm spacing"), std::string::npos) << i.out;
  const Outcome j = run({"info", "--json", path("layer.pdef")});
  ASSERT_EQ(j.exit_code, 0) << j.err;
  const auto info = nlohmann::json::parse(j.out)[0];
  const auto& residual = info["pdef"]["residual"];
  ASSERT_TRUE(residual.is_object()) << j.out;
  EXPECT_TRUE(residual["complete"].get<bool>());
  EXPECT_EQ(residual["bytes_read"], residual["stream_bytes"]);
  const auto width = residual["width"].get<std::size_t>(), height = residual["height"].get<std::size_t>();
  EXPECT_NE(i.out.find(fmt::format("decoded on the layer's {} x {} grid", width, height)), std::string::npos)
      << i.out;
  // The counts are the default decode's: every node of the layer's grid but those of trimmed cells.
  EXPECT_LE(info["vertices"].get<std::size_t>(), width * height);
  EXPECT_GT(info["vertices"].get<std::size_t>(), width * height / 2);

  // A prefix of the layer: the bytes read say so.
  const std::string bytes = slurp(work_ / "layer.pdef");
  const std::size_t offset = [&] {
    for (const auto& s : info["pdef"]["sections"])
      if (s["name"] == "residual stream") return s["offset"].get<std::size_t>();
    return std::size_t{0};
  }();
  ASSERT_GT(offset, 0U) << j.out;
  std::ofstream(work_ / "prefix.pdef", std::ios::binary) << bytes.substr(0, offset + 200);
  const Outcome p = run({"info", path("prefix.pdef")});
  ASSERT_EQ(p.exit_code, 0) << p.err;
  EXPECT_NE(p.out.find("a prefix of the stream: 200 of "), std::string::npos) << p.out;

  // Curves only: no layer, and the 1 mm note.
  ASSERT_EQ(run({"encode", path("face.ply"), "-o", path("curves.pdef")}).exit_code, 0);
  const Outcome c = run({"info", "--json", path("curves.pdef")});
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_TRUE(nlohmann::json::parse(c.out)[0]["pdef"]["residual"].is_null()) << c.out;
  EXPECT_NE(run({"info", path("curves.pdef")}).out.find("about 1 mm spacing"), std::string::npos);
}

TEST_F(PdefCli, EncodeInfoDecode) {
  const Outcome e = run({"encode", path("face.ply"), "-o", path("face.pdef")});
  ASSERT_EQ(e.exit_code, 0) << e.err;
  EXPECT_NE(e.out.find("28 curves x 30 points (10.0 % of 300)"), std::string::npos) << e.out;
  EXPECT_NE(e.out.find("bytes, lossy: samples on a"), std::string::npos) << e.out;
  const std::string bytes = slurp(work_ / "face.pdef");
  EXPECT_TRUE(bytes.starts_with("PDEF"));
  EXPECT_NE(e.out.find(std::to_string(bytes.size()) + " bytes"), std::string::npos) << e.out;

  const Outcome i = run({"info", path("face.pdef")});
  ASSERT_EQ(i.exit_code, 0) << i.err;
  EXPECT_NE(i.out.find("format          PDEF (" + std::to_string(bytes.size()) + " bytes)"),
            std::string::npos)
      << i.out;
  EXPECT_NE(i.out.find("curves          28 x 30 samples"), std::string::npos) << i.out;
  EXPECT_NE(i.out.find("surface         spline scheme, N = 29 modes + remainder"), std::string::npos)
      << i.out;
  EXPECT_NE(i.out.find("bytes           header 10, face "), std::string::npos) << i.out;
  EXPECT_NE(i.out.find("attributes      positions, normals"), std::string::npos) << i.out;

  const Outcome j = run({"info", "--json", path("face.pdef")});
  ASSERT_EQ(j.exit_code, 0) << j.err;
  const auto info = nlohmann::json::parse(j.out)[0];
  EXPECT_EQ(info["format"], "PDEF");
  EXPECT_EQ(info["pdef"]["curves"], 28);
  EXPECT_EQ(info["pdef"]["samples_per_curve"], 30);
  EXPECT_EQ(info["pdef"]["lossless"], false);
  std::size_t total = 0;
  for (const auto& s : info["pdef"]["sections"])
    total += s["bytes"].get<std::size_t>();
  EXPECT_EQ(total, bytes.size());

  for (const char* ext : {"glb", "obj", "ply", "wrl", "drc", "off", "stl", "gltf"}) {
    const std::string out = path(std::string("surface.") + ext);
    const Outcome d = run({"decode", path("face.pdef"), "-o", out});
    ASSERT_EQ(d.exit_code, 0) << ext << ": " << d.err;
    EXPECT_NE(d.out.find("in the scan's frame (mm)"), std::string::npos) << d.out;
    const Result<formats::LoadedMesh> mesh = formats::read_mesh(std::filesystem::path(out));
    ASSERT_TRUE(mesh) << mesh.error().to_string();
    EXPECT_GT(mesh->mesh.triangle_count(), 30000U) << ext;
  }
  ASSERT_EQ(run({"decode", path("face.pdef"), "-o", path("coarse.ply"), "--resolution", "30x40"}).exit_code,
            0);
  EXPECT_EQ(formats::read_mesh(work_ / "coarse.ply")->mesh.vertex_count(), 1200U);
  ASSERT_EQ(run({"decode", path("face.pdef"), "-o", path("tall.ply"), "--resolution", "50"}).exit_code, 0);
  EXPECT_EQ(formats::read_mesh(work_ / "tall.ply")->mesh.vertex_count() % 50, 0U);
}

TEST_F(PdefCli, LosslessAndOptions) {
  Outcome e = run({"encode", path("face.ply"), "-o", path("exact.pdef"), "--lossless", "--store-landmarks",
                   "--name", "sample", "--ratio", "0.2"});
  ASSERT_EQ(e.exit_code, 0) << e.err;
  EXPECT_NE(e.out.find("28 curves x 60 points"), std::string::npos) << e.out;
  EXPECT_NE(e.out.find("lossless"), std::string::npos) << e.out;
  const Outcome j = run({"info", "--json", path("exact.pdef")});
  ASSERT_EQ(j.exit_code, 0) << j.err;
  const auto info = nlohmann::json::parse(j.out)[0]["pdef"];
  EXPECT_EQ(info["lossless"], true);
  EXPECT_EQ(info["name"], "sample");
  EXPECT_TRUE(info["landmarks"].contains("nose_tip"));
  e = run({"encode", path("face.ply"), "-o", path("coarse.pdef"), "--max-error", "0.2"});
  ASSERT_EQ(e.exit_code, 0) << e.err;
  EXPECT_LT(slurp(work_ / "coarse.pdef").size(), slurp(work_ / "exact.pdef").size());
}

TEST_F(PdefCli, ConvertEncodesAScanAndDecodesAFile) {
  Outcome c = run({"convert", path("face.ply"), path("face.pdef")});
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_TRUE(slurp(work_ / "face.pdef").starts_with("PDEF"));
  c = run({"convert", path("face.pdef"), path("back.glb")});
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_NE(c.out.find("(PDEF, "), std::string::npos) << c.out;
  EXPECT_GT(formats::read_mesh(work_ / "back.glb")->mesh.vertex_count(), 15000U);
}

TEST_F(PdefCli, BadInputIsOneLineWithTheFileAndTheByte) {
  ASSERT_EQ(run({"encode", path("face.ply"), "-o", path("face.pdef")}).exit_code, 0);
  const std::string bytes = slurp(work_ / "face.pdef");
  std::ofstream(work_ / "cut.pdef", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  std::string damaged = bytes;
  damaged[40] = static_cast<char>(damaged[40] ^ 4);
  std::ofstream(work_ / "damaged.pdef", std::ios::binary) << damaged;
  const std::size_t before = files();
  const std::string cut_at = "byte " + std::to_string(bytes.size() / 2) + ": truncated";
  expect_data_error({"decode"}, {path("cut.pdef"), "-o", path("x.glb")}, cut_at, "cut.pdef");
  expect_data_error({"info"}, {path("cut.pdef")}, cut_at, "cut.pdef");
  expect_data_error({"convert"}, {path("cut.pdef"), path("x.ply")}, cut_at, "cut.pdef");
  expect_data_error({"decode"}, {path("damaged.pdef"), "-o", path("x.glb")},
                    "byte " + std::to_string(bytes.size() - 4) + ": checksum mismatch", "damaged.pdef");
  expect_data_error({"decode"}, {path("face.ply"), "-o", path("x.glb")}, "byte 0: bad magic", "face.ply");
  EXPECT_EQ(files(), before); // no output, no temporary file
}

TEST_F(PdefCli, WhatIsNotAFaceOrNotAFileIsRefused) {
  std::ofstream(work_ / "tetra.off")
      << "OFF\n4 4 0\n0 0 0\n10 0 0\n0 10 0\n0 0 10\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const std::size_t before = files();
  Outcome r = run({"encode", path("tetra.off"), "-o", path("tetra.pdef")});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(lines(r.err), 1U) << r.err;
  r = run({"convert", path("tetra.off"), path("tetra.pdef")});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  // Usage errors: exit 2, one line, nothing written.
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"encode", path("face.ply"), "-o", path("face.glb")},
        {"encode", path("face.ply"), "-o", path("face.pdef"), "--max-error", "0"},
        {"encode", path("face.ply")},
        {"decode", path("face.ply"), "-o", path("x.glb"), "--resolution", "1"},
        {"decode", path("absent.pdef"), "-o", path("x.glb")}}) {
    r = run(args);
    EXPECT_EQ(r.exit_code, 2) << args[0] << " " << r.err;
    EXPECT_EQ(lines(r.err), 1U) << r.err;
  }
  EXPECT_EQ(files(), before);
}

} // namespace
} // namespace pdeface::test

namespace pdeface::test {
namespace {

// The texture layer (encode --texture): the sample face's vertex colours over the face as a JPEG section,
// shown by `info`, decoded into a textured mesh that a GLB carries (the image embedded) and the validator
// passes; a scan without colour is refused and nothing is written.
TEST_F(PdefCli, TextureLayerFromVertexColours) {
  const Outcome e = run({"encode", path("face.ply"), "-o", path("t.pdef"), "--texture", "--texel", "1"});
  ASSERT_EQ(e.exit_code, 0) << e.err;
  EXPECT_NE(e.out.find("texture layer: "), std::string::npos) << e.out;
  EXPECT_NE(e.out.find("from the scan's vertex colours"), std::string::npos) << e.out;
  const Outcome i = run({"info", "--json", path("t.pdef")});
  ASSERT_EQ(i.exit_code, 0) << i.err;
  const nlohmann::json info = nlohmann::json::parse(i.out);
  bool listed = false;
  for (const auto& s : info[0]["pdef"]["sections"])
    listed = listed || s["name"] == "texture";
  EXPECT_TRUE(listed) << i.out;
  const Outcome d = run({"decode", path("t.pdef"), "-o", path("t.glb")});
  ASSERT_EQ(d.exit_code, 0) << d.err;
  const Result<formats::LoadedMesh> glb = formats::read_mesh(work_ / "t.glb");
  ASSERT_TRUE(glb) << glb.error().to_string();
  ASSERT_TRUE(glb->mesh.material && glb->mesh.material->base_color_image);
  EXPECT_EQ(glb->mesh.material->base_color_image->mime_type, "image/jpeg");
  EXPECT_EQ(glb->mesh.texcoords.size(), glb->mesh.vertex_count());
  if (const auto node = find_node(); node)
    if (const auto validator = find_validator(); validator)
      expect_valid_gltf(*node, *validator, work_ / "t.glb");

  // No colour: refused, no file.
  ASSERT_EQ(run({"convert", path("face.ply"), path("plain.stl")}).exit_code, 0);
  const Outcome plain = run({"encode", path("plain.stl"), "-o", path("plain.pdef"), "--texture"});
  EXPECT_EQ(plain.exit_code, 1) << plain.err;
  EXPECT_NE(plain.err.find("no colour for a texture layer"), std::string::npos) << plain.err;
  EXPECT_FALSE(std::filesystem::exists(work_ / "plain.pdef"));
  EXPECT_NE(run({"encode", path("face.ply"), "-o", path("x.pdef"), "--texel", "1"}).exit_code, 0)
      << "--texel needs --texture";
}

} // namespace
} // namespace pdeface::test

namespace pdeface::test {
namespace {

// james.obj's photograph through the texture layer: the decoded GLB passes the validator and, in three.js
// in headless Chromium (tools/gltf_viewer), shows a skin-coloured face; the file is 10-40 KB.
TEST_F(PdefCli, JamesTextureLayerShowsHisPhotoInAViewer) {
  PDEFACE_FACE_OR_SKIP(james, "james.obj");
  const Outcome e = run({"encode", james.string(), "-o", path("james.pdef"), "--texture"});
  ASSERT_EQ(e.exit_code, 0) << e.err;
  EXPECT_NE(e.out.find("from the scan's photograph"), std::string::npos) << e.out;
  const std::size_t bytes = slurp(work_ / "james.pdef").size();
  EXPECT_GT(bytes, 10'000U);
  EXPECT_LT(bytes, 40'000U);
  ASSERT_EQ(run({"decode", path("james.pdef"), "-o", path("james.glb")}).exit_code, 0);
  const auto node = find_node();
  if (!node) GTEST_SKIP() << "node is not on PATH";
  if (const auto validator = find_validator(); validator)
    expect_valid_gltf(*node, *validator, work_ / "james.glb");
  if (!std::filesystem::exists("/usr/bin/chromium"))
    GTEST_SKIP() << "no /usr/bin/chromium (apt-get install chromium)";
  const std::filesystem::path viewer = fixtures().parent_path().parent_path() / "tools" / "gltf_viewer";
  if (!std::filesystem::exists(viewer / "node_modules" / "three"))
    GTEST_SKIP() << "the viewer's packages are missing: cd tools/gltf_viewer && npm install";
  const std::string command = quoted(*node) + quoted(viewer / "screenshot.mjs") +
                              quoted(work_ / "james.glb") + quoted(work_ / "james.png") + "> " +
                              quoted(work_ / "james.json") + "2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const nlohmann::json stats = nlohmann::json::parse(slurp(work_ / "james.json"), nullptr, false);
  ASSERT_TRUE(stats.is_object()) << slurp(work_ / "james.json");
  EXPECT_EQ(stats["textured"], nlohmann::json::array({true})) << stats.dump();
  EXPECT_GT(stats["covered"].get<double>(), 0.15) << stats.dump();
  EXPECT_GT(stats["mean_saturation"].get<double>(), 20.0) << stats.dump();
  EXPECT_GT(stats["mean_rgb"][0].get<double>(), stats["mean_rgb"][2].get<double>() + 20.0) << stats.dump();
}

} // namespace
} // namespace pdeface::test

// .pdef on the command line: encode, decode, info and convert, with good and bad input.

#include "cli_fixture.hpp"

#include "pdeface/formats/formats.hpp"
#include "pdeface_test.hpp"

#include <nlohmann/json.hpp>

#include <fstream>

namespace pdeface::test {
namespace {

class PdefCli : public Cli {
protected:
  void SetUp() override { ASSERT_EQ(run({"sample", path("face.ply")}).exit_code, 0); }
};

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

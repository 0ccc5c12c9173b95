// The CLI driven as a user drives it: exit codes, what goes to stdout and stderr, files left behind.

#include "cli_fixture.hpp"

#include "pdeface/core/sample_face.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface_test.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

namespace pdeface {
namespace {

using test::Cli;
using test::lines;
using test::Outcome;
using test::slurp;

TEST_F(Cli, VersionAndHelp) {
  Outcome v = run({"--version"});
  EXPECT_EQ(v.exit_code, 0);
  EXPECT_NE(v.out.find("pdeface 0."), std::string::npos);
  for (const char* cmd : {"info", "convert", "sample", "align", "profiles", "reconstruct", "table", "compare",
                          "encode", "decode"}) {
    Outcome h = run({cmd, "--help"});
    EXPECT_EQ(h.exit_code, 0) << cmd;
    EXPECT_NE(h.out.find("Usage"), std::string::npos) << cmd;
  }
}

TEST_F(Cli, UsageErrorsAreOneLineAndExitTwo) {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{},
        {"frobnicate"},
        {"info"},
        {"info", path("absent.ply")},
        {"convert", "--draco-bits", "25", path("a.ply"), path("b.drc")}}) {
    Outcome r = run(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(lines(r.err), 1U) << r.err;
    EXPECT_TRUE(r.err.starts_with("pdeface")) << r.err;
  }
}

TEST_F(Cli, SampleThenInfo) {
  Outcome s = run({"sample", path("face.ply")});
  ASSERT_EQ(s.exit_code, 0) << s.err;
  Outcome i = run({"info", path("face.ply")});
  ASSERT_EQ(i.exit_code, 0) << i.err;
  EXPECT_NE(i.out.find("format          PLY"), std::string::npos) << i.out;
  EXPECT_NE(i.out.find("boundary loops  5"), std::string::npos) << i.out;
  EXPECT_NE(i.out.find("units           mm"), std::string::npos) << i.out;
}

TEST_F(Cli, InfoJsonIsMachineReadable) {
  ASSERT_EQ(run({"sample", path("face.obj")}).exit_code, 0);
  ASSERT_EQ(run({"sample", "--no-holes", path("face.wrl")}).exit_code, 0);
  Outcome r = run({"info", "--json", path("face.obj"), path("face.wrl")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j.size(), 2U);
  EXPECT_EQ(j[0]["format"], "OBJ");
  EXPECT_EQ(j[1]["format"], "VRML");
  EXPECT_EQ(j[0]["boundary_loops"], 5);
  EXPECT_EQ(j[1]["boundary_loops"], 1);
  EXPECT_EQ(j[0]["components"], 1);
  EXPECT_GT(j[0]["vertices"].get<int>(), 12000);
  EXPECT_EQ(j[0]["bbox"]["min"].size(), 3U);
}

TEST_F(Cli, ConvertEveryWritableFormatAndBack) {
  ASSERT_EQ(run({"sample", path("face.ply")}).exit_code, 0);
  const Outcome ref = run({"info", "--json", path("face.ply")});
  const auto expected = nlohmann::json::parse(ref.out)[0];
  for (const char* ext : {"wrl", "obj", "off", "stl", "glb", "gltf", "drc"}) {
    const std::string out = path(std::string("face.") + ext);
    Outcome c = run({"convert", path("face.ply"), out});
    ASSERT_EQ(c.exit_code, 0) << ext << ": " << c.err;
    Outcome i = run({"info", "--json", out});
    ASSERT_EQ(i.exit_code, 0) << ext << ": " << i.err;
    const auto got = nlohmann::json::parse(i.out)[0];
    EXPECT_EQ(got["vertices"], expected["vertices"]) << ext;
    EXPECT_EQ(got["triangles"], expected["triangles"]) << ext;
  }
}

TEST_F(Cli, DroppedAttributesAreNoted) {
  ASSERT_EQ(run({"sample", path("face.ply")}).exit_code, 0);
  Outcome r = run({"convert", path("face.ply"), path("face.stl")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("vertex colours dropped: STL cannot store them"), std::string::npos) << r.err;
}

TEST_F(Cli, BadInputGivesOneLineNamingTheFileAndLeavesNoOutput) {
  const auto bad = work_ / "broken.ply";
  std::ofstream(bad) << "ply\nformat binary_little_endian 1.0\nelement vertex 1000\nproperty float x\n";
  const std::size_t before = files();
  Outcome r = run({"convert", bad.string(), path("out.glb")});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(lines(r.err), 1U) << r.err;
  EXPECT_NE(r.err.find("broken.ply"), std::string::npos) << r.err;
  EXPECT_EQ(files(), before) << "no output, no temporary file";

  std::ofstream(work_ / "garbage.wrl") << "\x01\x02 not a mesh at all";
  Outcome g = run({"info", path("garbage.wrl")});
  EXPECT_EQ(g.exit_code, 1);
  EXPECT_NE(g.err.find("garbage.wrl"), std::string::npos) << g.err;
}

TEST_F(Cli, UnknownOutputExtensionIsRefusedBeforeWriting) {
  ASSERT_EQ(run({"sample", path("face.ply")}).exit_code, 0);
  const std::size_t before = files();
  Outcome r = run({"convert", path("face.ply"), path("face.xyz")});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("cannot tell the output format"), std::string::npos) << r.err;
  EXPECT_EQ(files(), before);
}

TEST_F(Cli, InfoKeepsGoingAfterABadFile) {
  ASSERT_EQ(run({"sample", path("face.obj")}).exit_code, 0);
  std::ofstream(work_ / "empty.obj");
  Outcome r = run({"info", path("empty.obj"), path("face.obj")});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("empty.obj"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("face.obj"), std::string::npos) << r.out;
}

TEST_F(Cli, AlignWritesTheMeshLandmarksAndPreview) {
  ASSERT_EQ(run({"sample", path("face.ply")}).exit_code, 0);
  Outcome a = run({"align", path("face.ply"), "-o", path("aligned.ply"), "--crop", "--preview",
                   path("face.svg"), "--landmarks-out", path("landmarks.json")});
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_NE(a.out.find("face found, confidence"), std::string::npos) << a.out;
  EXPECT_NE(a.out.find("cropped to the face"), std::string::npos) << a.out;
  const std::string svg = slurp(work_ / "face.svg");
  EXPECT_TRUE(svg.starts_with("<svg")) << svg.substr(0, 80);
  EXPECT_NE(svg.find("nose_tip"), std::string::npos);
  const auto landmarks = nlohmann::json::parse(slurp(work_ / "landmarks.json"));
  EXPECT_EQ(landmarks["landmarks"].size(), 9U);
  EXPECT_TRUE(landmarks.contains("to_canonical"));

  // The landmarks found can be given back instead of detecting again.
  Outcome given =
      run({"align", path("face.ply"), "-o", path("again.obj"), "--landmarks", path("landmarks.json")});
  ASSERT_EQ(given.exit_code, 0) << given.err;
  EXPECT_NE(given.out.find("landmarks given"), std::string::npos) << given.out;
}

TEST_F(Cli, AlignFailsCleanlyWithoutAFace) {
  // A flat sheet: symmetric every which way, but no nose.
  std::string off = "OFF\n1600 0 0\n";
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j)
      off += std::to_string(4 * i) + " " + std::to_string(4 * j) + " 0\n";
  std::ofstream(work_ / "sheet.off") << off;
  const std::size_t before = files();
  Outcome r = run({"align", path("sheet.off"), "-o", path("aligned.ply")});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(lines(r.err), 1U) << r.err;
  EXPECT_NE(r.err.find("sheet.off"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("no face found"), std::string::npos) << r.err;
  EXPECT_EQ(files(), before) << "no output";

  ASSERT_EQ(run({"sample", path("face.ply")}).exit_code, 0);
  std::ofstream(work_ / "bad.json") << "{\"landmarks\": {\"nose_tip\": [1, 2]}}";
  Outcome b = run({"align", path("face.ply"), "-o", path("x.ply"), "--landmarks", path("bad.json")});
  EXPECT_EQ(b.exit_code, 1);
  EXPECT_NE(b.err.find("bad.json"), std::string::npos) << b.err;
  EXPECT_NE(b.err.find("three finite numbers"), std::string::npos) << b.err;
}

TEST_F(Cli, ProfilesWritesTheCurvesAndThePicture) {
  ASSERT_EQ(run({"sample", path("face.ply")}).exit_code, 0);
  Outcome r = run(
      {"profiles", path("face.ply"), "--ratio", "0.2", "-o", path("face.json"), "--svg", path("face.svg")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(lines(r.out), 1U) << r.out;
  EXPECT_NE(r.out.find("28 curves"), std::string::npos) << r.out;
  const auto json = nlohmann::json::parse(slurp(work_ / "face.json"));
  EXPECT_EQ(json["format"], "pdeface-profiles");
  ASSERT_EQ(json["curves"].size(), 28U);
  EXPECT_EQ(json["curves"][0]["points"].size(), json["points_per_curve"]);
  EXPECT_NEAR(json["sampling_ratio"].get<double>(), 0.2, 0.01);
  EXPECT_EQ(json["evaluation"].size(), 4U);
  EXPECT_TRUE(slurp(work_ / "face.svg").starts_with("<svg"));

  // Given landmarks, other counts and K directly.
  ASSERT_EQ(run({"align", path("face.ply"), "-o", path("aligned.ply"), "--landmarks-out", path("lm.json")})
                .exit_code,
            0);
  Outcome given = run({"profiles", path("face.ply"), "--landmarks", path("lm.json"), "--curves", "16",
                       "--points", "12", "--parameter", "height", "-o", path("given.json")});
  ASSERT_EQ(given.exit_code, 0) << given.err;
  const auto g = nlohmann::json::parse(slurp(work_ / "given.json"));
  EXPECT_EQ(g["curves"].size(), 16U);
  EXPECT_EQ(g["points_per_curve"], 12);
  EXPECT_EQ(g["parameter"], "height");
}

TEST_F(Cli, ProfilesFailsCleanlyAndWritesNothing) {
  ASSERT_EQ(run({"sample", path("face.ply")}).exit_code, 0);
  // Landmarks that put the face beside the scan: bad data, however well formed the file is.
  std::ofstream(io_ / "beside.json")
      << R"({"format": "pdeface-landmarks", "version": 1, "units": "mm", "landmarks": {
  "nose_tip": [500, 0, 0], "eye_inner_left": [517, 29, -20], "eye_inner_right": [483, 29, -20],
  "eye_outer_left": [546, 30, -30], "eye_outer_right": [454, 30, -30], "mouth_left": [523, -30, -15],
  "mouth_right": [477, -30, -15], "face_top": [500, 70, -15], "face_bottom": [500, -80, -20]}})";
  const std::size_t before = files();
  for (const auto& [args, expect] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"--curves", "27"}, "3 · patches + 1"},
           {{"--landmarks", (io_ / "beside.json").string()}, "most of the face is missing"}}) {
    expect_data_error({"profiles", path("face.ply"), "-o", path("out.json"), "--svg", path("out.svg")}, args,
                      expect, "face.ply");
    EXPECT_EQ(files(), before) << "no output after " << args[0];
  }
  // Wrong on the command line itself: exit 2, one line.
  for (const std::vector<std::string>& args : {std::vector<std::string>{"--parameter", "index"},
                                               {"--ratio", "0.7"},
                                               {"--ratio", "0.01"},
                                               {"--points", "2"},
                                               {"--points", "12", "--ratio", "0.2"}}) {
    std::vector<std::string> cmd{"profiles", path("face.ply"), "-o", path("out.json")};
    cmd.insert(cmd.end(), args.begin(), args.end());
    Outcome usage = run(cmd);
    EXPECT_EQ(usage.exit_code, 2) << args[0] << " " << args[1];
    EXPECT_NE(usage.err.find(args[0]), std::string::npos) << usage.err;
  }
  EXPECT_EQ(files(), before);
}

TEST_F(Cli, ReconstructWritesTheSurfaceInTheScansUnits) {
  ASSERT_EQ(run({"sample", path("face.ply")}).exit_code, 0);
  Mesh metres = sample_face(); // the scan stated in metres
  for (Vec3& p : metres.positions)
    p /= 1000.0;
  metres.units = Units::Metres;
  ASSERT_TRUE(formats::write_mesh(metres, work_ / "face.glb"));
  Outcome r = run({"reconstruct", path("face.glb"), "-o", path("surface.ply"), "--profiles",
                   path("curves.json"), "--resolution", "60x80"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(lines(r.out), 6U) << r.out;
  EXPECT_NE(r.out.find(" m in the scan's units"), std::string::npos) << r.out;
  // The same distances in metres: a thousandth of the millimetres (printed to 3 decimals and to 3
  // significant digits).
  double mean_mm = 0.0, mean_m = 0.0;
  const std::size_t at_mm = r.out.find("surface distance mean ");
  const std::size_t at_m = r.out.find("= mean ");
  ASSERT_NE(at_mm, std::string::npos) << r.out;
  ASSERT_NE(at_m, std::string::npos) << r.out;
  ASSERT_EQ(std::sscanf(r.out.c_str() + at_mm, "surface distance mean %lf", &mean_mm), 1) << r.out;
  ASSERT_EQ(std::sscanf(r.out.c_str() + at_m, "= mean %lf", &mean_m), 1) << r.out;
  EXPECT_GT(mean_mm, 0.0);
  EXPECT_NEAR(mean_m, mean_mm / 1000.0, 0.006 * mean_mm / 1000.0 + 0.0005 / 1000.0) << r.out;
  EXPECT_NE(r.out.find("self-check on the face: mean distance"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("coverage of the face"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("28 curves"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("spline scheme"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("60 x 80 grid, 4800 vertices"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("profile error"), std::string::npos) << r.out;
  const auto curves = nlohmann::json::parse(slurp(work_ / "curves.json"));
  EXPECT_EQ(curves["curves"].size(), 28U);
  Outcome info = run({"info", "--json", path("surface.ply")});
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const auto j = nlohmann::json::parse(info.out)[0];
  EXPECT_EQ(j["vertices"], 4800);
  EXPECT_EQ(j["triangles"], 2 * 59 * 79);
  EXPECT_EQ(j["units"], "m");
  EXPECT_LT(j["bbox"]["size"][0].get<double>(), 0.3); // a face in metres, not millimetres

  Outcome paper = run({"reconstruct", path("face.ply"), "-o", path("paper.obj"), "--scheme", "paper",
                       "--smoothing", "1", "--spacing", "uniform", "--ratio", "0.2", "--modes", "10"});
  ASSERT_EQ(paper.exit_code, 0) << paper.err;
  EXPECT_NE(paper.out.find("paper scheme, N = 10 modes + remainder, a = 1.000"), std::string::npos)
      << paper.out;
}

// A result its own self-check finds off (4 curves cannot hold a face: 2.8 mm from the scan on average) is
// refused with what failed and by how much, nothing written and an existing output left as it was; with
// --force it is written, with a warning.
TEST_F(Cli, AResultThatFailsItsSelfCheckIsNotWritten) {
  ASSERT_EQ(run({"sample", path("face.ply")}).exit_code, 0);
  {
    std::ofstream old(work_ / "out.glb");
    old << "the user's earlier file";
  }
  const std::size_t before = files();
  for (const std::string output : {"out.glb", "out.pdef"}) {
    const std::string command = output == "out.glb" ? "reconstruct" : "encode";
    const std::vector<std::string> args{command, path("face.ply"), "-o", path(output), "--curves", "4"};
    const Outcome r = run(args);
    EXPECT_EQ(r.exit_code, 1) << command << ": " << r.err;
    EXPECT_EQ(lines(r.err), 1U) << r.err;
    EXPECT_NE(r.err.find("self-check failed"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("mean distance to the scan"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("face.ply"), std::string::npos) << r.err;
    EXPECT_EQ(files(), before) << command;
    EXPECT_EQ(slurp(work_ / "out.glb"), "the user's earlier file");
  }
  const Outcome forced =
      run({"reconstruct", path("face.ply"), "-o", path("out.glb"), "--curves", "4", "--force"});
  EXPECT_EQ(forced.exit_code, 0) << forced.err;
  EXPECT_NE(forced.err.find("warning: written with --force although its self-check failed"),
            std::string::npos)
      << forced.err;
  EXPECT_NE(slurp(work_ / "out.glb"), "the user's earlier file");
}

TEST_F(Cli, ReconstructFailsCleanlyAndWritesNothing) {
  ASSERT_EQ(run({"sample", path("face.ply")}).exit_code, 0);
  const std::size_t before = files();
  for (const auto& [args, expect] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"--scheme", "patch4", "--smoothing", "50"}, "patch4 would amplify"},
           {{"--modes", "5000"}, "modes asked for"}}) {
    expect_data_error(
        {"reconstruct", path("face.ply"), "-o", path("out.glb"), "--profiles", path("out.json")}, args,
        expect, "face.ply");
    EXPECT_EQ(files(), before) << "no output after " << args[0];
  }
  // An output format that does not exist is found before anything is written: not even the curves.
  expect_data_error({"reconstruct", path("face.ply"), "--profiles", path("out.json")},
                    {"-o", path("out.xyz")}, "cannot tell the output format", "out.xyz");
  EXPECT_EQ(files(), before);
  // The outputs are written as a set: one that cannot be (its folder is missing) leaves none behind, the
  // mesh and the preview named before it included.
  const Outcome unwritable = run({"reconstruct", path("face.ply"), "-o", path("out.glb"), "--preview",
                                  path("out.svg"), "--profiles", path("no/such/folder/out.json")});
  EXPECT_EQ(unwritable.exit_code, 1);
  EXPECT_NE(unwritable.err.find("error: " + path("no/such/folder/out.json")), std::string::npos)
      << unwritable.err;
  EXPECT_EQ(files(), before);
  for (const std::vector<std::string>& args : {std::vector<std::string>{"--resolution", "1x5"},
                                               {"--resolution", "10x10x10"},
                                               {"--scheme", "bezier"}}) {
    std::vector<std::string> cmd{"reconstruct", path("face.ply"), "-o", path("out.glb")};
    cmd.insert(cmd.end(), args.begin(), args.end());
    EXPECT_EQ(run(cmd).exit_code, 2) << args[1];
  }
  // Not a face at all.
  std::ofstream(work_ / "flat.obj") << "v 0 0 0\nv 100 0 0\nv 0 100 0\nv 100 100 0\nf 1 2 3\nf 2 4 3\n";
  Outcome flat = run({"reconstruct", path("flat.obj"), "-o", path("out.glb")});
  EXPECT_EQ(flat.exit_code, 1);
  EXPECT_NE(flat.err.find("flat.obj"), std::string::npos) << flat.err;
  EXPECT_EQ(files(), before + 1);
}

TEST_F(Cli, TableWritesMarkdownAndCsv) {
  ASSERT_EQ(run({"sample", path("a.ply")}).exit_code, 0);
  ASSERT_EQ(run({"sample", "--seed", "3", path("b.obj")}).exit_code, 0);
  Outcome r = run({"table", path("a.ply"), path("b.obj"), "--ratios", "0.05,0.2", "--schemes", "spline,paper",
                   "-o", path("t.md"), "--csv", path("t.csv")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("2 scans x 2 ratios x 2 schemes"), std::string::npos) << r.out;
  const std::string md = slurp(work_ / "t.md");
  EXPECT_NE(md.find("| ratio | K | spline | paper |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 20 % |"), std::string::npos) << md;
  EXPECT_EQ(lines(slurp(work_ / "t.csv")), 1U + 2 * 2 * 2);

  Outcome out = run({"table", path("a.ply"), "--ratios", "0.1", "--schemes", "spline"});
  ASSERT_EQ(out.exit_code, 0) << out.err;
  EXPECT_TRUE(out.out.starts_with("# Profile error")) << out.out;
}

TEST_F(Cli, TableFailsOnAnyBadScanAndWritesNothing) {
  ASSERT_EQ(run({"sample", path("a.ply")}).exit_code, 0);
  std::ofstream(work_ / "broken.ply") << "ply\nformat ascii 1.0\nelement vertex 3\n";
  const std::size_t before = files();
  Outcome r = run({"table", path("a.ply"), path("broken.ply"), "-o", path("t.md"), "--csv", path("t.csv")});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("broken.ply"), std::string::npos) << r.err;
  EXPECT_EQ(files(), before);
  EXPECT_EQ(run({"table", path("a.ply"), "--ratios", "0.7"}).exit_code, 2);
  EXPECT_EQ(run({"table", path("a.ply"), "--schemes", "spline,nurbs"}).exit_code, 2);
}

TEST_F(Cli, CompareWithNoInputIsTheMainJob) {
  const Outcome r = run_in_work({"compare"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("sample face: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("draco 11 bits"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("pde 10 % lossy"), std::string::npos) << r.out;
  EXPECT_EQ(r.err.find("error"), std::string::npos) << r.err;
  const auto dir = work_ / "pdeface-report";
  for (const char* name : {"report.md", "report.json", "report.csv", "rd.svg", "report.html"})
    EXPECT_GT(std::filesystem::file_size(dir / name), 1000U) << name;
  std::size_t glbs = 0, textured = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    glbs += entry.path().extension() == ".glb" ? 1 : 0;
    textured += entry.path().string().ends_with("_textured.glb") ? 1 : 0;
  }
  EXPECT_EQ(glbs, 3U + 5U) << "3 heat maps, and the colour rows (the sample's vertex colours) textured";
  EXPECT_EQ(textured, 5U);
  EXPECT_NE(r.out.find("3 heat-map GLBs, 5 textured GLBs"), std::string::npos) << r.out;
  const std::string md = slurp(dir / "report.md");
  EXPECT_TRUE(md.starts_with("# pdeface compare")) << md.substr(0, 200);
  EXPECT_NE(md.find("| decimate+draco 1024 B |"), std::string::npos);
  const auto j = nlohmann::json::parse(slurp(dir / "report.json"));
  EXPECT_EQ(j["scans"][0]["name"], "sample face");
}

TEST_F(Cli, CompareBatchReportsABadScanAndCompletesTheOthers) {
  std::filesystem::create_directories(work_ / "scans");
  ASSERT_EQ(run({"sample", path("scans/a.ply")}).exit_code, 0);
  ASSERT_EQ(run({"sample", "--seed", "3", path("scans/b.obj")}).exit_code, 0);
  std::ofstream(work_ / "scans" / "broken.ply") << "ply\nformat ascii 1.0\nelement vertex 3\n";
  std::ofstream(work_ / "scans" / "notes.txt") << "not a scan\n";
  // A hostile one (issue 22): 100 random vertices a kilometre apart, which ran detection for minutes.
  std::ofstream soup(work_ / "scans" / "soup.obj");
  for (int i = 0; i < 100; ++i)
    soup << "v " << (i * 7919 % 1000) * 1000.0 << " " << (i * 104729 % 1000) * 1000.0 << " " << i * 9973.0
         << "\n";
  for (int i = 0; i < 300; ++i)
    soup << "f " << i % 100 + 1 << " " << (i * 37 + 11) % 100 + 1 << " " << (i * 53 + 29) % 100 + 1 << "\n";
  soup.close();
  const Outcome r =
      run({"compare", path("scans"), "--out", path("rep"), "--draco-bits", "11", "--budgets", "2048",
           "--ratios", "0.1", "--lossy-only", "--decimate-bits", "10,11,12", "--pdef-sizes", "2048"});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("error: " + path("scans/broken.ply")), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("error: " + path("scans/soup.obj")), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("4 scans (2 failed)"), std::string::npos) << r.out;
  const std::string md = slurp(work_ / "rep" / "report.md");
  EXPECT_NE(md.find("## broken.ply: failed"), std::string::npos) << md;
  EXPECT_NE(md.find("## a.ply: "), std::string::npos) << md;
  EXPECT_NE(md.find("## b.obj: "), std::string::npos) << md;
  EXPECT_EQ(md.find("notes.txt"), std::string::npos) << md;
  const std::string csv = slurp(work_ / "rep" / "report.csv");
  EXPECT_NE(md.find("## soup.obj: failed"), std::string::npos) << md;
  // 2 scans x rows (raw and gzip, Draco, decimate + Draco at the budget and at the .pdef's size, the .pdef,
  // with a residual layer, and colour: Draco with the vertex colours and 4 texture layers), the failed
  // scans'.
  EXPECT_EQ(lines(csv), 1U + 2U * (8 + 1 + 2 + 1 + 1 + 5) + 2U) << csv;
  EXPECT_NE(md.find("pde 5 % + residual 2048 B"), std::string::npos) << md;
  EXPECT_NE(md.find("Rate and distortion"), std::string::npos) << md;

  EXPECT_EQ(run({"compare", "--ratios", "0.8"}).exit_code, 2);
  EXPECT_EQ(run({"compare", path("absent.ply")}).exit_code, 2);
  EXPECT_EQ(run({"compare", "--draco-bits", "30"}).exit_code, 2);
}

} // namespace
} // namespace pdeface

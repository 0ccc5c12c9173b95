// pdeface compare: PDE .pdef against Draco, decimation + Draco and raw meshes, in size and fidelity, on the
// given scans (or the built-in sample face), written as a report folder.

#include "common.hpp"

#include "pdeface/core/text.hpp"
#include "pdeface/pipeline/report.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <unistd.h>

namespace pdeface::cli {
namespace {

struct CompareArgs {
  std::vector<fs::path> in;
  fs::path out = "pdeface-report";
  pipeline::CompareOptions options;
  std::string scheme = "spline";
  bool lossy_only = false;
  bool lossless_only = false;
  bool no_pde_budgets = false;
  bool no_colour = false;
  bool files = false;
  bool quiet = false;
};

// Progress on stderr: a bar redrawn in place on a terminal, a line per finished scan otherwise.
class ProgressPrinter {
public:
  explicit ProgressPrinter(bool quiet) : quiet_(quiet), terminal_(isatty(fileno(stderr)) != 0) {}
  void operator()(const pipeline::Progress& p) {
    const bool failed = p.event == pipeline::ProgressEvent::Failed;
    if (quiet_ || !terminal_) {
      if (failed) // always said
        fmt::print(stderr, "pdeface: error: {}\n", p.failure);
      else if (!quiet_ && p.event == pipeline::ProgressEvent::Done)
        fmt::print(stderr, "pdeface: [{}/{}] {}: {}\n", p.scans_done, p.scans_total, p.scan, p.what());
      return;
    }
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double share =
        p.steps_total ? static_cast<double>(p.steps_done) / static_cast<double>(p.steps_total) : 0;
    const int filled = static_cast<int>(share * 30.0);
    std::string eta = "--:--";
    if (share > 0.02) {
      const auto left = static_cast<int>(elapsed * (1.0 - share) / share);
      eta = fmt::format("{}:{:02}", left / 60, left % 60);
    }
    // Cut at a character boundary: a scan's name may be any UTF-8.
    const std::string what = excerpt(p.scan + ": " + p.what(), 40);
    fmt::print(stderr, "\r[{}{}] {}/{} scans{} {:3.0f} %  ETA {}  {:<41}", std::string(filled, '#'),
               std::string(30 - filled, ' '), p.scans_done, p.scans_total,
               p.scans_failed ? fmt::format(" ({} failed)", p.scans_failed) : std::string(), 100.0 * share,
               eta, what);
    if (failed) fmt::print(stderr, "\npdeface: error: {}\n", p.failure);
    if (p.scans_done == p.scans_total) fmt::print(stderr, "\n");
  }

private:
  bool quiet_, terminal_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

int run_compare(CompareArgs args) {
  Result<std::vector<fs::path>> inputs = pipeline::expand_inputs(args.in);
  if (!inputs) return fail(inputs.error());
  if (!args.in.empty() && inputs->empty()) {
    fmt::print(stderr, "pdeface: error: no mesh files in {}\n", args.in.front().string());
    return kDataError;
  }
  pipeline::CompareOptions& o = args.options;
  o.scheme = named<pde::Scheme>(pde::kSchemeNames, args.scheme);
  o.pde_lossless = !args.lossy_only;
  o.pde_lossy = !args.lossless_only;
  o.budgets_at_pde = !args.no_pde_budgets;
  o.colour = !args.no_colour;
  o.keep_bytes = args.files;
  ProgressPrinter printer(args.quiet);
  const pipeline::Report report =
      pipeline::compare_scans({.inputs = *inputs, .options = o, .progress = std::ref(printer)});
  const Result<std::size_t> files = pipeline::write_report(report, args.out);
  if (!files) return fail(files.error());

  for (const pipeline::ScanReport& s : report.scans) {
    if (!s.failure.empty()) {
      fmt::print("{}: failed: {}\n", s.source, s.failure);
      continue;
    }
    const auto find = [&](pipeline::Method m, std::string_view name) -> const pipeline::Variant* {
      for (const pipeline::Variant& v : s.variants)
        if (v.method == m && (name.empty() || v.name == name) && v.fidelity) return &v;
      return nullptr;
    };
    fmt::print("{}: {} vertices, PLY {} bytes, {} variants in {:.1f} s\n", s.source, s.vertices, s.ply_bytes,
               s.variants.size(), s.seconds);
    for (const pipeline::Variant* v :
         {find(pipeline::Method::Draco, fmt::format("draco {} bits", o.heat_draco_bits)),
          find(pipeline::Method::DecimateDraco, "decimate+draco 2048 B"),
          find(pipeline::Method::Pde, fmt::format("pde {:g} % lossy", 100 * o.heat_ratio))})
      if (v)
        fmt::print("  {:<28} {:>8} bytes  coverage {:5.1f} %  mask -> mesh mean {:.3f} mm  mesh -> scan mean "
                   "{:.3f} mm\n",
                   v->name, v->bytes, 100 * v->fidelity->coverage.share, v->fidelity->coverage.distance.mean,
                   v->fidelity->to_scan.mean);
  }
  std::size_t heat = 0, textured = 0;
  for (const pipeline::ScanReport& s : report.scans) {
    heat += s.heat_maps.size();
    textured += s.textured.size();
  }
  const std::size_t encoded = *files - 5 - heat - textured; // with --files
  const auto count = [](std::size_t n, std::string_view what) {
    return fmt::format("{} {}{}", n, what, n == 1 ? "" : "s");
  };
  fmt::print("{} ({} failed) -> {}/report.md, report.html, report.json, report.csv, rd.svg, {}{}{}\n",
             count(report.scans.size(), "scan"), report.failed(), args.out.string(),
             count(heat, "heat-map GLB"),
             textured > 0 ? ", " + count(textured, "textured GLB") : std::string(),
             encoded > 0 ? ", " + count(encoded, "encoded file") : std::string());
  return report.failed() > 0 ? kDataError : 0;
}

} // namespace

void compare_command(CLI::App& app, int& status) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "PDE .pdef against Draco, decimation + Draco and raw meshes, in size and fidelity, on the "
                 "given scans and folders (default: the built-in sample face); writes a report folder");
  cmd->add_option("input", args->in, "Scans and folders of scans (any readable format)")
      ->check(CLI::ExistingPath);
  cmd->add_option("-o,--out", args->out, "Report folder")->capture_default_str();
  cmd->add_option("--ratios", args->options.ratios, "PDE sampling ratios, comma-separated (0.05..0.6)")
      ->delimiter(',')
      ->check(CLI::Range(slice::kMinRatio, slice::kMaxRatio))
      ->capture_default_str();
  cmd->add_option("--scheme", args->scheme, "PDE scheme")
      ->check(one_of<pde::Scheme>(pde::kSchemeNames))
      ->capture_default_str();
  cmd->add_flag("--lossy-only", args->lossy_only, "Only the lossy .pdef variants");
  cmd->add_flag("--lossless-only", args->lossless_only, "Only the lossless .pdef variants")
      ->excludes("--lossy-only");
  cmd->add_option("--draco-bits", args->options.draco_bits,
                  "Draco quantisation bits, comma-separated (1..24)")
      ->delimiter(',')
      ->check(CLI::Range(1, 24))
      ->capture_default_str();
  cmd->add_option("--draco-level", args->options.draco_level, "Draco compression level (0..10)")
      ->check(CLI::Range(0, 10))
      ->capture_default_str();
  cmd->add_option("--budgets", args->options.budgets, "Decimate + Draco byte budgets, comma-separated")
      ->delimiter(',')
      ->check(CLI::Range(std::size_t{64}, std::size_t{1} << 30))
      ->capture_default_str();
  cmd->add_option("--pdef-sizes", args->options.pde_budgets,
                  "Sizes of the .pdef with a residual layer (encode --size), comma-separated")
      ->delimiter(',')
      ->check(CLI::Range(std::size_t{64}, std::size_t{1} << 26))
      ->capture_default_str();
  cmd->add_option("--decimate-bits", args->options.decimate_bits,
                  "Quantisation bits tried per budget (the least error is kept)")
      ->delimiter(',')
      ->check(CLI::Range(1, 24))
      ->capture_default_str();
  cmd->add_flag("--no-pde-budgets", args->no_pde_budgets,
                "No decimate + Draco rows at the .pdef variants' sizes");
  cmd->add_option("--heat-max", args->options.heat_max_mm, "Heat maps: the error shown red, mm")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_flag(
      "--no-colour", args->no_colour,
      "No colour rows (Draco with the photograph, the .pdef with a texture layer) on scans that have "
      "colour");
  cmd->add_option("--draco-uv-bits", args->options.draco_uv_bits,
                  "Colour rows: Draco's texture coordinate bits (as draco_encoder -qt)")
      ->check(CLI::Range(1, 24))
      ->capture_default_str();
  cmd->add_flag("--crop-face", args->options.crop_face,
                "Compress only the face (no ears, neck, shoulders or pedestal), as a .pdef holds it");
  cmd->add_flag("--files", args->files, "Also write every variant's encoded file (DIR/files/SCAN/)");
  cmd->add_option("--threads", args->options.threads,
                  "Threads per scan (default: shared out over the cores)");
  cmd->add_flag("-q,--quiet", args->quiet, "No progress on stderr");
  cmd->callback([args, &status] { status = run_compare(*args); });
}

} // namespace pdeface::cli

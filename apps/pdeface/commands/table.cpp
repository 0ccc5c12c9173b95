// pdeface table: the paper's Table I on the given scans.

#include "common.hpp"

#include "pdeface/pipeline/requests.hpp"

#include <fmt/format.h>

#include <cstdio>

namespace pdeface::cli {
namespace {

struct TableArgs {
  std::vector<fs::path> in;
  fs::path out; // Markdown; stdout when empty
  fs::path csv;
  std::vector<double> ratios{pipeline::kPaperRatios.begin(), pipeline::kPaperRatios.end()};
  std::vector<std::string> schemes{"spline", "paper", "patch4"};
  CurveArgs curves;
  SurfaceArgs surface;
};

int run_table(const TableArgs& args) {
  pipeline::TableOptions options{.ratios = args.ratios,
                                 .schemes = {},
                                 .profiles = args.curves.profile_options(),
                                 .pde = args.surface.pde_options()};
  for (const std::string& name : args.schemes)
    options.schemes.push_back(named<pde::Scheme>(pde::kSchemeNames, name));
  std::vector<pipeline::TableRow> rows;
  for (const fs::path& in : args.in) {
    Result<formats::LoadedMesh> scan = read_scan(in);
    if (!scan) return fail(scan.error());
    Result<std::vector<pipeline::TableRow>> scan_rows =
        pipeline::table_request(scan->mesh, options, in.string());
    if (!scan_rows) return fail(scan_rows.error());
    for (const pipeline::TableRow& r : *scan_rows)
      if (!r.fidelity)
        fmt::print(stderr, "pdeface: note: {}: {:g} %, {}: {}\n", in.string(), 100 * r.ratio,
                   pde::to_string(r.scheme), r.failure);
    rows.insert(rows.end(), scan_rows->begin(), scan_rows->end());
  }
  const std::string markdown = pipeline::table_markdown(rows);
  std::vector<OutputFile> outputs;
  if (!args.out.empty()) outputs.push_back({args.out, markdown});
  if (!args.csv.empty()) outputs.push_back({args.csv, pipeline::table_csv(rows)});
  if (Result<void> ok = write_outputs(outputs); !ok) return fail(ok.error());
  if (args.out.empty())
    fmt::print("{}", markdown);
  else
    fmt::print("{} scans x {} ratios x {} schemes -> {}\n", args.in.size(), args.ratios.size(),
               options.schemes.size(), args.out.string());
  return 0;
}

} // namespace

void table_command(CLI::App& app, int& status) {
  auto args = std::make_shared<TableArgs>();
  CLI::App* cmd =
      app.add_subcommand("table", "The paper's Table I on the given scans: profile error, surface "
                                  "distance and face coverage per sampling ratio and scheme, as "
                                  "Markdown (and CSV)");
  cmd->add_option("input", args->in, "Scans (any readable format)")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", args->out, "Markdown file to write (default: standard output)");
  cmd->add_option("--csv", args->csv, "Also write every row as CSV");
  cmd->add_option("--ratios", args->ratios, "Sampling ratios, comma-separated (0.05..0.6)")
      ->delimiter(',')
      ->check(CLI::Range(slice::kMinRatio, slice::kMaxRatio))
      ->capture_default_str();
  cmd->add_option("--schemes", args->schemes, "Schemes to compare, comma-separated")
      ->delimiter(',')
      ->check(one_of<pde::Scheme>(pde::kSchemeNames))
      ->capture_default_str();
  args->curves.add_to(cmd, /*with_landmarks=*/false);
  args->surface.add_to(cmd, /*with_scheme=*/false);
  cmd->callback([args, &status] { status = run_table(*args); });
}

} // namespace pdeface::cli

// pdeface convert: any readable format to any writable one (a scan to .pdef through `encode`, a .pdef to
// its surface)

#include "common.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cstdio>

namespace pdeface::cli {
namespace {

struct ConvertRequest {
  fs::path in;
  fs::path out;
  std::string from;
  std::string to;
  formats::WriteOptions write;
  bool no_companions = false;
};

int run_convert(ConvertRequest request) {
  formats::ReadOptions read;
  read.companions = !request.no_companions;
  for (auto [name, format] : {std::pair{&request.from, &read.format}, {&request.to, &request.write.format}}) {
    if (name->empty()) continue;
    Result<formats::Format> parsed = formats::format_from_name(*name);
    if (!parsed) return fail(parsed.error());
    *format = *parsed;
  }
  // A .pdef holds a face's curves, which only a scan gives: the scan is encoded as `pdeface encode` does.
  if (request.write.format.value_or(formats::format_from_path(request.out).value_or(formats::Format::Ply)) ==
      formats::Format::Pdef) {
    pipeline::EncodeRequest encode;
    encode.source = request.in.string();
    return encode_scan(request.in, request.out, encode);
  }
  Notes notes;
  Result<formats::ConvertReport> report =
      formats::convert(request.in, request.out, read, request.write, &notes);
  print_notes(notes);
  if (!report) return fail(report.error());
  fmt::print("{} ({}, {} bytes) -> {} ({}, {} bytes): {} vertices, {} triangles\n", request.in.string(),
             formats::info(report->from).name, report->bytes_in, request.out.string(),
             formats::info(report->to).name, report->bytes_out, report->vertices, report->triangles);
  return 0;
}

} // namespace

void convert_command(CLI::App& app, int& status) {
  auto request = std::make_shared<ConvertRequest>();
  ConvertRequest& r = *request;
  CLI::App* cmd =
      app.add_subcommand("convert", "Convert between formats chosen by extension: ." +
                                        fmt::format("{}", fmt::join(formats::format_names(), " .")));
  add_input(cmd, r.in, "File to read");
  cmd->add_option("output", r.out, "File to write (replaced atomically)")->required();
  cmd->add_option("--from", r.from, "Input format when the extension is misleading (e.g. ply)");
  cmd->add_option("--to", r.to, "Output format when the extension is misleading (e.g. glb)");
  cmd->add_flag("--no-companions", r.no_companions,
                "Read no file the input refers to (an OBJ's material library and image, a glTF's or VRML's "
                "image)");
  add_write_options(cmd, r.write);
  cmd->callback([request, &status] { status = run_convert(*request); });
}

} // namespace pdeface::cli

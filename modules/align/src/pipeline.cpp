#include "pdeface/align/pipeline.hpp"

#include "pdeface/align/frame.hpp"
#include "pdeface/align/preview.hpp"

#include <fmt/format.h>

#include <filesystem>

namespace pdeface::align {

Result<Alignment> align_from(const Mesh& scan, const LandmarkSource& landmarks, std::string_view source) {
  if (!landmarks.bytes) return align_scan(scan, std::nullopt, source, {}, landmarks.detect);
  Result<Landmarks> given = read_landmarks(*landmarks.bytes, landmarks.name);
  if (!given) return given.error();
  return align_scan(scan, *std::move(given), source, landmarks.name);
}

Result<AlignOutcome> align_request(const Mesh& scan, const AlignRequest& request) {
  Result<Alignment> alignment = align_from(scan, request.landmarks, request.source);
  if (!alignment) return alignment.error();
  AlignOutcome out{*alignment, to_canonical(scan, alignment->frame), {}, {}};
  if (request.crop) {
    Result<Mesh> cropped =
        crop_face(out.canonical, to_canonical(alignment->landmarks, alignment->frame), request.crop_options);
    if (!cropped) return with_source(std::move(cropped).error(), request.source);
    out.canonical = std::move(cropped).value();
  }
  if (request.landmarks_json)
    out.landmarks_json = write_alignment_json(alignment->landmarks, alignment->frame, alignment->confidence);
  if (request.preview) {
    const std::string name = std::filesystem::path(request.source).filename().string();
    const std::string title =
        alignment->confidence
            ? fmt::format("{}: found, confidence {:.2f}", name, *alignment->confidence)
            : fmt::format("{}: landmarks from {}", name,
                          std::filesystem::path(request.landmarks.name).filename().string());
    out.preview_svg = preview_svg(scan, alignment->frame, alignment->landmarks, {.title = title});
  }
  return out;
}

} // namespace pdeface::align

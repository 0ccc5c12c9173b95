#include "pdeface/align/landmarks.hpp"

#include "pdeface/core/text.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <initializer_list>

namespace pdeface::align {
namespace {

using nlohmann::json;

constexpr std::array<std::string_view, kLandmarkCount> kNames{
    "nose_tip",   "eye_inner_left", "eye_inner_right", "eye_outer_left", "eye_outer_right",
    "mouth_left", "mouth_right",    "face_top",        "face_bottom"};

Error json_error(const json::parse_error& e, std::string_view bytes, std::string_view source) {
  // nlohmann reports the byte after the offending token (1-based); point at the token itself.
  const std::uint64_t offset = e.byte > 0 ? e.byte - 1 : 0;
  std::string what = e.what();
  if (const auto colon = what.rfind(": "); colon != std::string::npos) what = what.substr(colon + 2);
  return make_error(ErrorCode::Malformed, "invalid JSON: " + excerpt(what, 200), std::string(source),
                    Location::in_text(bytes, offset));
}

Result<json> parse_json(std::string_view bytes, std::string_view source) {
  if (bytes.empty()) return make_error(ErrorCode::Empty, "the file is empty", std::string(source));
  try {
    return json::parse(bytes);
  } catch (const json::parse_error& e) {
    return json_error(e, bytes, source);
  }
}

// A JSON array of three finite numbers.
std::optional<Vec3> to_point(const json& j) {
  if (!j.is_array() || j.size() != 3) return std::nullopt;
  Vec3 p;
  for (int i = 0; i < 3; ++i) {
    if (!j[static_cast<std::size_t>(i)].is_number()) return std::nullopt;
    p[i] = j[static_cast<std::size_t>(i)].get<double>();
  }
  if (!p.allFinite()) return std::nullopt;
  return p;
}

// The face's forward direction implied by the eyes and mouth: (left - right) x (eyes - mouth) points
// out of the face when "left" is the face's own left.
bool left_and_right_swapped(const Landmarks& l) {
  using L = Landmark;
  for (L needed : {L::NoseTip, L::EyeOuterLeft, L::EyeOuterRight, L::MouthLeft, L::MouthRight})
    if (!l.has(needed)) return false;
  const Vec3 eyes = 0.5 * (*l[L::EyeOuterLeft] + *l[L::EyeOuterRight]);
  const Vec3 mouth = 0.5 * (*l[L::MouthLeft] + *l[L::MouthRight]);
  const Vec3 forward = (*l[L::EyeOuterLeft] - *l[L::EyeOuterRight]).cross(eyes - mouth);
  return forward.dot(*l[L::NoseTip] - 0.5 * (eyes + mouth)) < 0.0;
}

void swap_left_and_right(Landmarks& l) {
  for (std::size_t i = 0; i < kLandmarkCount; ++i) {
    const auto a = static_cast<Landmark>(i);
    const Landmark b = mirrored(a);
    if (static_cast<std::size_t>(b) > i) std::swap(l[a], l[b]);
  }
}

} // namespace

std::string_view name(Landmark landmark) noexcept { return kNames[static_cast<std::size_t>(landmark)]; }

std::optional<Landmark> landmark_from_name(std::string_view n) noexcept {
  const auto it = std::ranges::find(kNames, n);
  if (it == kNames.end()) return std::nullopt;
  return static_cast<Landmark>(it - kNames.begin());
}

Landmark mirrored(Landmark l) noexcept {
  switch (l) {
  case Landmark::EyeInnerLeft: return Landmark::EyeInnerRight;
  case Landmark::EyeInnerRight: return Landmark::EyeInnerLeft;
  case Landmark::EyeOuterLeft: return Landmark::EyeOuterRight;
  case Landmark::EyeOuterRight: return Landmark::EyeOuterLeft;
  case Landmark::MouthLeft: return Landmark::MouthRight;
  case Landmark::MouthRight: return Landmark::MouthLeft;
  default: return l;
  }
}

std::size_t Landmarks::count() const {
  return static_cast<std::size_t>(std::ranges::count_if(points, [](const auto& p) { return p.has_value(); }));
}

namespace {

Result<Landmarks> from_ours(const json& j, std::string_view source) {
  auto fail = [&](std::string message) {
    return make_error(ErrorCode::Malformed, std::move(message), std::string(source));
  };
  if (!j.is_object() || !j.contains("landmarks") || !j["landmarks"].is_object())
    return fail("expected an object with a \"landmarks\" object (see docs/align.md)");
  if (j.contains("version") && j["version"] != 1)
    return make_error(ErrorCode::UnsupportedVersion,
                      fmt::format("landmark file version {} (we read 1)", excerpt(j["version"].dump())),
                      std::string(source));
  Landmarks out;
  if (j.contains("units")) {
    const std::optional<Units> units =
        j["units"].is_string() ? units_from_string(j["units"].get<std::string>()) : std::nullopt;
    if (!units) return fail(fmt::format("unknown units {} (mm, cm, m or in)", excerpt(j["units"].dump())));
    out.units = *units;
  }
  for (const auto& [key, value] : j["landmarks"].items()) {
    const std::optional<Landmark> l = landmark_from_name(key);
    if (!l)
      return fail(
          fmt::format("unknown landmark \"{}\" (known: nose_tip, eye_inner_left, ...)", excerpt(key)));
    const std::optional<Vec3> p = to_point(value);
    if (!p)
      return fail(fmt::format("landmark \"{}\" must be three finite numbers, not {}", excerpt(key),
                              excerpt(value.dump())));
    out[*l] = p;
  }
  return out;
}

Result<Landmarks> from_ljson(const json& j, std::string_view source) {
  auto fail = [&](std::string message) {
    return make_error(ErrorCode::Malformed, std::move(message), std::string(source));
  };
  if (!j.is_object()) return fail("expected a menpo LJSON object");

  // Version 2-3: groups -> {labels: [{label, mask}], landmarks: {points}}; version 1: top-level
  // landmarks.points and labels.
  const json* group = &j;
  if (j.contains("groups") && j["groups"].is_object() && !j["groups"].empty())
    group = &j["groups"].begin().value();
  if (!group->contains("landmarks") || !(*group)["landmarks"].contains("points") ||
      !(*group)["landmarks"]["points"].is_array())
    return fail("no landmarks.points array (not a menpo LJSON file?)");
  const json& points = (*group)["landmarks"]["points"];

  auto point = [&](std::size_t index) -> Result<Vec3> {
    if (index >= points.size())
      return fail(fmt::format("mask index {} is out of range: there are {} points", index, points.size()));
    const std::optional<Vec3> p = to_point(points[index]);
    if (!p)
      return fail(
          fmt::format("point {} is not three finite numbers (2D landmarks cannot place a 3D face)", index));
    return *p;
  };
  // The k-th point of the first label named one of `names`; nullopt if there is no such label.
  auto labelled = [&](std::initializer_list<std::string_view> names,
                      std::size_t k) -> Result<std::optional<Vec3>> {
    if (!group->contains("labels") || !(*group)["labels"].is_array()) return std::optional<Vec3>{};
    for (const json& label : (*group)["labels"]) {
      if (!label.contains("label") || !label["label"].is_string()) continue;
      if (std::ranges::find(names, label["label"].get<std::string>()) == names.end()) continue;
      const json& mask = label.value("mask", json::array());
      if (!mask.is_array() || k >= mask.size() || !mask[k].is_number_unsigned())
        return fail(fmt::format("label \"{}\" has no point {}", label["label"].get<std::string>(), k));
      Result<Vec3> p = point(mask[k].get<std::size_t>());
      if (!p) return std::move(p).error();
      return std::optional<Vec3>(*p);
    }
    return std::optional<Vec3>{};
  };

  // iBUG 68: jaw 0-16 (chin 8), nose 27-35 (tip 30), image-left eye 36-41 (outer 36, inner 39), image-right
  // eye 42-47 (inner 42, outer 45), mouth 48-67 (corners 48, 54). The image-left eye is the face's right.
  struct Rule {
    Landmark landmark;
    std::initializer_list<std::string_view> labels;
    std::size_t k;    // position inside the label's mask
    std::size_t ibug; // index in a plain 68-point list
  };
  const Rule rules[] = {
      {Landmark::NoseTip, {"nose"}, 3, 30},
      {Landmark::EyeOuterRight, {"leye", "left_eye"}, 0, 36},
      {Landmark::EyeInnerRight, {"leye", "left_eye"}, 3, 39},
      {Landmark::EyeInnerLeft, {"reye", "right_eye"}, 0, 42},
      {Landmark::EyeOuterLeft, {"reye", "right_eye"}, 3, 45},
      {Landmark::MouthRight, {"mouth"}, 0, 48},
      {Landmark::MouthLeft, {"mouth"}, 6, 54},
      {Landmark::FaceBottom, {"chin", "jaw"}, 8, 8},
  };
  Landmarks out;
  for (const Rule& rule : rules) {
    Result<std::optional<Vec3>> p = labelled(rule.labels, rule.k);
    if (!p) return std::move(p).error();
    if (!*p && points.size() == 68) {
      Result<Vec3> q = point(rule.ibug);
      if (!q) return std::move(q).error();
      *p = *q;
    }
    if (!*p)
      return fail(fmt::format("cannot find {}: neither iBUG labels nor 68 points", name(rule.landmark)));
    out[rule.landmark] = **p;
  }
  // Conventions differ on whether "left" is the image's or the face's; the geometry decides.
  if (left_and_right_swapped(out)) swap_left_and_right(out);
  return out;
}

} // namespace

std::string write_landmarks_json(const Landmarks& landmarks) {
  json j;
  j["format"] = "pdeface-landmarks";
  j["version"] = 1;
  if (landmarks.units != Units::Unknown) j["units"] = to_string(landmarks.units);
  json points = json::object();
  for (std::size_t i = 0; i < kLandmarkCount; ++i)
    if (const auto& p = landmarks.points[i]) points[std::string(kNames[i])] = {p->x(), p->y(), p->z()};
  j["landmarks"] = std::move(points);
  return j.dump(2) + "\n";
}

Result<Landmarks> read_landmarks_json(std::string_view bytes, std::string_view source) {
  Result<json> parsed = parse_json(bytes, source);
  if (!parsed) return std::move(parsed).error();
  return from_ours(*parsed, source);
}

Result<Landmarks> read_ljson(std::string_view bytes, std::string_view source) {
  Result<json> parsed = parse_json(bytes, source);
  if (!parsed) return std::move(parsed).error();
  return from_ljson(*parsed, source);
}

Result<Landmarks> read_landmarks(std::string_view bytes, std::string_view source) {
  Result<json> parsed = parse_json(bytes, source);
  if (!parsed) return std::move(parsed).error();
  const json& j = *parsed;
  const bool menpo =
      j.is_object() && (j.contains("groups") || (j.contains("landmarks") && j["landmarks"].is_object() &&
                                                 j["landmarks"].contains("points")));
  return menpo ? from_ljson(j, source) : from_ours(j, source);
}

} // namespace pdeface::align

#pragma once
// Names and numbers of glTF 2.0 shared by the reader and the writer.

#include <string_view>

namespace pdeface::gltf {

inline constexpr std::string_view kDracoExtension = "KHR_draco_mesh_compression";
inline constexpr std::string_view kQuantizationExtension = "KHR_mesh_quantization";
//! Our units marker: `asset.extras.units` ("mm", "cm", "m", "in"). glTF says metres, but scanners write
//! millimetres into it, so units are known only when this marker states them.
inline constexpr std::string_view kUnitsKey = "units";

//! Number of components of an accessor type ("VEC3" -> 3); 0 when unknown.
[[nodiscard]] constexpr int components_of(std::string_view type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4" || type == "MAT2") return 4;
  if (type == "MAT3") return 9;
  if (type == "MAT4") return 16;
  return 0;
}

} // namespace pdeface::gltf

// Writes the hand-made Draco fixtures of this folder with libdraco itself, for the cases our writer
// refuses to produce (it validates meshes first). Not part of the build; to regenerate:
//   g++ -std=c++17 make_fixtures.cpp -o /tmp/make_fixtures -ldraco && /tmp/make_fixtures .
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iostream>
#include <limits>
#include <string>

namespace {

// A 2x2-quad square (9 points, 8 triangles) with unquantised float positions; optionally a generic
// attribute of 16 components (unique id 1), like a matrix per vertex.
std::unique_ptr<draco::Mesh> square(int nan_at_point, bool wide = false) {
  auto mesh = std::make_unique<draco::Mesh>();
  mesh->set_num_points(9);
  draco::GeometryAttribute ga;
  ga.Init(draco::GeometryAttribute::POSITION, nullptr, 3, draco::DT_FLOAT32, false, 12, 0);
  const int id = mesh->AddAttribute(ga, true, 9);
  for (int i = 0; i < 9; ++i) {
    std::array<float, 3> p{float(i % 3), float(i / 3), 0.0f};
    if (i == nan_at_point) p[2] = std::numeric_limits<float>::quiet_NaN();
    mesh->attribute(id)->SetAttributeValue(draco::AttributeValueIndex(i), p.data());
  }
  if (wide) {
    draco::GeometryAttribute generic;
    generic.Init(draco::GeometryAttribute::GENERIC, nullptr, 16, draco::DT_FLOAT32, false, 64, 0);
    const int g = mesh->AddAttribute(generic, true, 9);
    const std::array<float, 16> m{};
    for (int i = 0; i < 9; ++i)
      mesh->attribute(g)->SetAttributeValue(draco::AttributeValueIndex(i), m.data());
  }
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) {
      const int a = 3 * y + x;
      mesh->AddFace({draco::PointIndex(a), draco::PointIndex(a + 1), draco::PointIndex(a + 4)});
      mesh->AddFace({draco::PointIndex(a), draco::PointIndex(a + 4), draco::PointIndex(a + 3)});
    }
  return mesh;
}

// The square with its positions stored as BOOL (one byte per component, values 0, 1 and 2): a data type
// no position can have; libdraco's converter would load those bytes as bools.
std::unique_ptr<draco::Mesh> bool_square() {
  std::unique_ptr<draco::Mesh> mesh = square(-1);
  draco::GeometryAttribute ga;
  ga.Init(draco::GeometryAttribute::POSITION, nullptr, 3, draco::DT_BOOL, false, 3, 0);
  auto attribute = std::make_unique<draco::PointAttribute>(ga);
  attribute->SetIdentityMapping();
  attribute->Reset(9);
  for (int i = 0; i < 9; ++i) {
    const std::array<std::uint8_t, 3> p{std::uint8_t(i % 3), std::uint8_t(i / 3), 2};
    attribute->SetAttributeValue(draco::AttributeValueIndex(i), p.data());
  }
  mesh->SetAttribute(0, std::move(attribute));
  return mesh;
}

bool save(const std::string& path, const draco::Mesh& mesh) {
  draco::Encoder encoder; // no quantisation: positions are stored as raw floats
  encoder.SetSpeedOptions(10, 10);
  draco::EncoderBuffer buffer;
  if (!encoder.EncodeMeshToBuffer(mesh, &buffer).ok()) return false;
  std::ofstream(path, std::ios::binary).write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
  return true;
}

} // namespace

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : ".";
  if (!save(dir + "/nan_position.drc", *square(4)) || !save(dir + "/square.drc", *square(-1)) ||
      !save(dir + "/square_generic16.drc", *square(-1, true)) ||
      !save(dir + "/bool_position.drc", *bool_square())) {
    std::cerr << "encoding failed\n";
    return 1;
  }
  return 0;
}

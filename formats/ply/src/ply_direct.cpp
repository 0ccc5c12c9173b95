// The PLY data read straight into a mesh, in one pass over the bytes, for the layouts every scanner and our
// own writer use (ply_layout.hpp, `read_direct`). It gives exactly what OpenMesh's reader gave for them:
// coordinates as float32 (ASCII correctly rounded to float, as `istream >> float` does), uchar colours
// divided by 255, polygons fan-triangulated from their first corner. It reports no errors itself: at the
// first value the validator would refuse it gives up, and the validator names the fault.

#include "ply_layout.hpp"

#include <fast_float/fast_float.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace pdeface::ply::detail {
namespace {

// Where a vertex value goes.
enum class Slot : std::uint8_t { X, Y, Z, NX, NY, NZ, U, V, Red, Green, Blue, Alpha, Skip };
constexpr std::size_t kSlots = 12;

Slot vertex_slot(std::string_view name) {
  constexpr std::array<std::pair<std::string_view, Slot>, 16> kNames{{{"x", Slot::X},
                                                                      {"y", Slot::Y},
                                                                      {"z", Slot::Z},
                                                                      {"nx", Slot::NX},
                                                                      {"ny", Slot::NY},
                                                                      {"nz", Slot::NZ},
                                                                      {"u", Slot::U},
                                                                      {"s", Slot::U},
                                                                      {"texture_u", Slot::U},
                                                                      {"v", Slot::V},
                                                                      {"t", Slot::V},
                                                                      {"texture_v", Slot::V},
                                                                      {"red", Slot::Red},
                                                                      {"green", Slot::Green},
                                                                      {"blue", Slot::Blue},
                                                                      {"alpha", Slot::Alpha}}};
  for (const auto& [n, slot] : kNames)
    if (n == name) return slot;
  return Slot::Skip;
}

struct Value {
  Scalar type;
  Slot slot;
};

// How the vertex and face elements are read; nullopt for a layout left to OpenMesh.
struct Plan {
  const Element* vertex = nullptr;
  const Element* face = nullptr;
  std::vector<Value> vertex_values;
  bool normals = false, texcoords = false, colors = false, alpha = false;
  std::size_t indices = 0; //!< which face property is the vertex_indices list
};

std::optional<Plan> make_plan(const Header& header) {
  Plan plan;
  for (const Element& e : header.elements) {
    if (e.name == "vertex") plan.vertex = &e;
    if (e.name == "face") plan.face = &e;
  }
  if (!plan.vertex) return std::nullopt;
  std::array<bool, kSlots> seen{};
  for (const Property& p : plan.vertex->properties) {
    Slot slot = p.role == Role::Ignored ? Slot::Skip : vertex_slot(p.name);
    if (p.role == Role::Coordinate && (slot == Slot::Skip || slot >= Slot::Red || p.type != Scalar::Float32))
      return std::nullopt; // double coordinates
    if (p.role == Role::Color && (slot < Slot::Red || slot == Slot::Skip || p.type != Scalar::UInt8))
      return std::nullopt; // float colours, diffuse_red ...
    if (slot != Slot::Skip) {
      if (seen[static_cast<std::size_t>(slot)]) return std::nullopt; // one value twice (u and s)
      seen[static_cast<std::size_t>(slot)] = true;
    }
    plan.vertex_values.push_back({p.type, slot});
  }
  auto has = [&](Slot s) { return seen[static_cast<std::size_t>(s)]; };
  plan.normals = has(Slot::NX) || has(Slot::NY) || has(Slot::NZ);
  plan.texcoords = has(Slot::U) || has(Slot::V);
  plan.colors = has(Slot::Red) || has(Slot::Green) || has(Slot::Blue) || has(Slot::Alpha);
  plan.alpha = has(Slot::Alpha);
  // Partial sets (nx without ny, alpha alone) are left to OpenMesh.
  if (plan.normals && !(has(Slot::NX) && has(Slot::NY) && has(Slot::NZ))) return std::nullopt;
  if (plan.texcoords && !(has(Slot::U) && has(Slot::V))) return std::nullopt;
  if (plan.colors && !(has(Slot::Red) && has(Slot::Green) && has(Slot::Blue))) return std::nullopt;
  if (plan.face) {
    std::size_t lists = 0;
    for (std::size_t k = 0; k < plan.face->properties.size(); ++k) {
      const Property& p = plan.face->properties[k];
      if (p.role == Role::Color) return std::nullopt; // face colours: a note OpenMesh's reader gives
      if (p.role != Role::Indices) continue;
      if (*p.count_type != Scalar::UInt8 && *p.count_type != Scalar::Int32) return std::nullopt;
      if (p.type == Scalar::Int16 || p.type == Scalar::UInt16) return std::nullopt;
      plan.indices = k;
      ++lists;
    }
    // OpenMesh skips properties before the list, wrongly: such files fail to read.
    if (lists != 1 || plan.indices != 0) return std::nullopt;
  }
  return plan;
}

// What the vertices and faces become.
struct Output {
  Mesh mesh;
  std::size_t short_faces = 0;
  std::uint32_t vertex_count = 0; //!< declared: faces may come before the vertices

  void start_vertices(const Plan& plan, std::size_t count) {
    mesh.positions.resize(count);
    if (plan.normals) mesh.normals.resize(count);
    if (plan.texcoords) mesh.texcoords.resize(count);
    if (plan.colors) mesh.colors.resize(count);
  }
  // One vertex's values, in slot order (colours as their integer value).
  void vertex(const Plan& plan, std::size_t i, const std::array<float, kSlots>& v) {
    mesh.positions[i] = Vec3(v[0], v[1], v[2]);
    if (plan.normals) mesh.normals[i] = Vec3f(v[3], v[4], v[5]);
    if (plan.texcoords) mesh.texcoords[i] = Vec2f(v[6], v[7]);
    if (plan.colors) mesh.colors[i] = Vec4f(Vec4f(v[8], v[9], v[10], v[11]) / 255.0f);
  }
};

// Polygons fan-triangulated as they arrive: (c0, c1, c2), (c0, c2, c3), ...
class Fan {
public:
  explicit Fan(Output& out) : out_(out) {}
  void corner(std::uint32_t v) {
    if (n_ == 0)
      first_ = v;
    else if (n_ >= 2)
      out_.mesh.triangles.push_back({first_, last_, v});
    last_ = v;
    ++n_;
  }
  void end() {
    if (n_ < 3) ++out_.short_faces;
    n_ = 0;
  }

private:
  Output& out_;
  std::uint32_t first_ = 0, last_ = 0;
  std::size_t n_ = 0;
};

bool is_integer_type(Scalar type) { return type != Scalar::Float32 && type != Scalar::Float64; }

bool integer_in_range(Scalar type, std::int64_t v) {
  auto within = [v]<class T>(T) {
    return v >= std::numeric_limits<T>::min() &&
           v <= static_cast<std::int64_t>(std::numeric_limits<T>::max());
  };
  switch (type) {
  case Scalar::Int8: return within(std::int8_t{});
  case Scalar::UInt8: return within(std::uint8_t{});
  case Scalar::Int16: return within(std::int16_t{});
  case Scalar::UInt16: return within(std::uint16_t{});
  case Scalar::Int32: return within(std::int32_t{});
  case Scalar::UInt32: return within(std::uint32_t{});
  case Scalar::Float32:
  case Scalar::Float64: return true;
  }
  return false;
}

// ---- binary -------------------------------------------------------------------------------------------

template <bool BigEndian> class Binary {
public:
  Binary(std::string_view bytes, std::size_t offset) : bytes_(bytes), pos_(offset) {}

  [[nodiscard]] std::size_t offset() const { return pos_; }

private:
  template <class T> T load(std::size_t at) const {
    if constexpr (sizeof(T) == 1) {
      return static_cast<T>(bytes_[at]);
    } else {
      using U = std::conditional_t<sizeof(T) == 2, std::uint16_t,
                                   std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>>;
      U raw;
      std::memcpy(&raw, bytes_.data() + at, sizeof raw);
      if constexpr (BigEndian != (std::endian::native == std::endian::big)) {
        if constexpr (sizeof(U) == 2) raw = __builtin_bswap16(raw);
        if constexpr (sizeof(U) == 4) raw = __builtin_bswap32(raw);
        if constexpr (sizeof(U) == 8) raw = __builtin_bswap64(raw);
      }
      return std::bit_cast<T>(raw);
    }
  }

  // An integer value of `type` at `at` (the caller has checked that its bytes are there).
  [[nodiscard]] std::int64_t integer(Scalar type, std::size_t at) const {
    switch (type) {
    case Scalar::Int8: return load<std::int8_t>(at);
    case Scalar::UInt8: return load<std::uint8_t>(at);
    case Scalar::Int16: return load<std::int16_t>(at);
    case Scalar::UInt16: return load<std::uint16_t>(at);
    case Scalar::Int32: return load<std::int32_t>(at);
    case Scalar::UInt32: return load<std::uint32_t>(at);
    case Scalar::Float32:
    case Scalar::Float64: break;
    }
    return -1;
  }
  [[nodiscard]] bool have(std::size_t n) const { return bytes_.size() - pos_ >= n; }

public:
  bool vertices(const Plan& plan, const Element& e, Output& out) {
    std::size_t record = 0;
    for (const Value& v : plan.vertex_values)
      record += size_of(v.type);
    if (e.count > (bytes_.size() - pos_) / record) return false; // truncated: the validator says where
    out.start_vertices(plan, e.count);
    // Where each slot's value is in the record; slots the file lacks read from a zero.
    std::array<std::size_t, kSlots> at{};
    std::size_t offset = 0;
    for (const Value& v : plan.vertex_values) {
      if (v.slot != Slot::Skip) at[static_cast<std::size_t>(v.slot)] = offset;
      offset += size_of(v.type);
    }
    const bool plain = !plan.normals && !plan.texcoords && !plan.colors;
    std::uint32_t bad = 0; // exponent bits all set: an infinity or a NaN
    auto coordinate = [&](std::size_t where) {
      const auto bits = load<std::uint32_t>(where);
      bad |= static_cast<std::uint32_t>((bits & 0x7f800000U) == 0x7f800000U);
      return std::bit_cast<float>(bits);
    };
    std::size_t base = pos_;
    if (plain) {
      for (std::size_t i = 0; i < e.count; ++i, base += record) {
        const float x = coordinate(base + at[0]);
        const float y = coordinate(base + at[1]);
        const float z = coordinate(base + at[2]);
        out.mesh.positions[i] = Vec3(x, y, z);
      }
    } else {
      std::array<float, kSlots> v{};
      for (std::size_t i = 0; i < e.count; ++i, base += record) {
        for (std::size_t s = 0; s < 3; ++s)
          v[s] = coordinate(base + at[s]);
        if (plan.normals)
          for (std::size_t s = 3; s < 6; ++s)
            v[s] = coordinate(base + at[s]);
        if (plan.texcoords)
          for (std::size_t s = 6; s < 8; ++s)
            v[s] = coordinate(base + at[s]);
        if (plan.colors) {
          for (std::size_t s = 8; s < 11; ++s)
            v[s] = static_cast<float>(load<std::uint8_t>(base + at[s]));
          v[11] = plan.alpha ? static_cast<float>(load<std::uint8_t>(base + at[11])) : 255.0f;
        }
        out.vertex(plan, i, v);
      }
    }
    if (bad != 0) return false;
    pos_ = base;
    return true;
  }

  bool faces(const Plan& plan, const Element& e, Output& out) {
    const std::vector<Property>& properties = e.properties;
    const Property& list = properties[plan.indices];
    const std::int64_t vertices = out.vertex_count;
    // A triangle takes at least 4 bytes (1-byte length and indices): reserve no more than the data can hold.
    out.mesh.triangles.reserve(std::min<std::size_t>(e.count, (bytes_.size() - pos_) / 4));
    // The common record: uchar 3, then three 32-bit indices, and nothing else.
    const bool common = !BigEndian && properties.size() == 1 && *list.count_type == Scalar::UInt8 &&
                        (list.type == Scalar::Int32 || list.type == Scalar::UInt32);
    Fan fan(out);
    for (std::size_t i = 0; i < e.count; ++i) {
      if (common && have(13) && bytes_[pos_] == 3) {
        const std::uint32_t a = load<std::uint32_t>(pos_ + 1);
        const std::uint32_t b = load<std::uint32_t>(pos_ + 5);
        const std::uint32_t c = load<std::uint32_t>(pos_ + 9);
        // A negative int index is above every vertex count as unsigned.
        if (a >= out.vertex_count || b >= out.vertex_count || c >= out.vertex_count) return false;
        out.mesh.triangles.push_back({a, b, c});
        pos_ += 13;
        continue;
      }
      for (const Property& p : properties) {
        if (&p != &list) {
          if (!have(size_of(p.type))) return false;
          pos_ += size_of(p.type);
          continue;
        }
        const std::size_t count_size = size_of(*p.count_type);
        if (!have(count_size)) return false;
        const std::int64_t n = integer(*p.count_type, pos_);
        pos_ += count_size;
        if (n < 0) return false;
        const std::size_t size = size_of(p.type);
        if (static_cast<std::uint64_t>(n) > (bytes_.size() - pos_) / size) return false;
        for (std::int64_t k = 0; k < n; ++k, pos_ += size) {
          const std::int64_t index = integer(p.type, pos_);
          if (index < 0 || index >= vertices) return false;
          fan.corner(static_cast<std::uint32_t>(index));
        }
        fan.end();
      }
    }
    return true;
  }

  // An element we do not read: its bytes passed over.
  bool skip(const Element& e) {
    const bool lists =
        std::ranges::any_of(e.properties, [](const Property& p) { return p.count_type.has_value(); });
    if (!lists) {
      std::size_t record = 0;
      for (const Property& p : e.properties)
        record += size_of(p.type);
      if (e.count > (bytes_.size() - pos_) / record) return false;
      pos_ += e.count * record;
      return true;
    }
    for (std::size_t i = 0; i < e.count; ++i)
      for (const Property& p : e.properties) {
        if (!p.count_type) {
          if (!have(size_of(p.type))) return false;
          pos_ += size_of(p.type);
          continue;
        }
        if (!have(size_of(*p.count_type))) return false;
        const std::int64_t n = integer(*p.count_type, pos_);
        pos_ += size_of(*p.count_type);
        if (n < 0 || static_cast<std::uint64_t>(n) > (bytes_.size() - pos_) / size_of(p.type)) return false;
        pos_ += static_cast<std::size_t>(n) * size_of(p.type);
      }
    return true;
  }

private:
  std::string_view bytes_;
  std::size_t pos_;
};

// ---- ASCII --------------------------------------------------------------------------------------------

// The blanks of text::Scanner: space, tab, CR, VT, FF and LF.
constexpr std::array<bool, 256> kBlank = [] {
  std::array<bool, 256> blank{};
  for (unsigned char c : {' ', '\t', '\r', '\v', '\f', '\n'})
    blank[c] = true;
  return blank;
}();

class Ascii {
public:
  Ascii(std::string_view bytes, std::size_t offset)
      : begin_(bytes.data()), p_(bytes.data() + offset), end_(bytes.data() + bytes.size()) {}

  // The offset of the next token, or of the end.
  std::size_t next_token() {
    skip_blanks();
    return static_cast<std::size_t>(p_ - begin_);
  }

private:
  [[nodiscard]] bool blank(const char* at) const { return kBlank[static_cast<unsigned char>(*at)]; }
  void skip_blanks() {
    while (p_ != end_ && blank(p_))
      ++p_;
  }
  // Strips one '+' as text::parse_real and text::parse_integer do ("+-1" stays and fails).
  [[nodiscard]] const char* start() const {
    return (*p_ == '+' && p_ + 1 != end_ && p_[1] != '-') ? p_ + 1 : p_;
  }
  // The parse ended at the end of the token.
  bool took(const char* end) {
    if (end != end_ && !blank(end)) return false;
    p_ = end;
    return true;
  }
  // The next token as a whole float; false if it is not one (or there is none).
  bool real(float& value) {
    skip_blanks();
    if (p_ == end_) return false;
    const char* from = start();
    const auto [end, ec] = fast_float::from_chars(from, end_, value);
    if (ec != std::errc() || end == from) return false;
    if (std::abs(value) >= FLT_MAX || !std::isfinite(value)) { // exactly as the validator: as a double
      double exact = 0;
      const auto [end2, ec2] = fast_float::from_chars(from, end_, exact);
      if (ec2 != std::errc() || !std::isfinite(exact) || std::abs(exact) > FLT_MAX) return false;
    }
    return took(end);
  }
  bool integer(std::int64_t& value) {
    skip_blanks();
    if (p_ == end_) return false;
    const char* from = start();
    const auto [end, ec] = std::from_chars(from, end_, value);
    if (ec != std::errc() || end == from) return false;
    return took(end);
  }
  // Any value of `type`, only checked.
  bool any(Scalar type) {
    if (is_integer_type(type)) {
      std::int64_t v = 0;
      return integer(v) && integer_in_range(type, v);
    }
    skip_blanks();
    if (p_ == end_) return false;
    const char* from = start();
    double v = 0;
    const auto [end, ec] = fast_float::from_chars(from, end_, v);
    if (ec != std::errc() || end == from) return false;
    return took(end);
  }

public:
  bool vertices(const Plan& plan, const Element& e, Output& out) {
    out.start_vertices(plan, e.count);
    std::array<float, kSlots> v{};
    v[11] = 255.0f;
    for (std::size_t i = 0; i < e.count; ++i) {
      for (const Value& value : plan.vertex_values) {
        if (value.slot == Slot::Skip) {
          if (!any(value.type)) return false;
        } else if (value.slot < Slot::Red) {
          if (!real(v[static_cast<std::size_t>(value.slot)])) return false;
        } else {
          std::int64_t c = 0;
          if (!integer(c) || c < 0 || c > 255) return false;
          v[static_cast<std::size_t>(value.slot)] = static_cast<float>(c);
        }
      }
      out.vertex(plan, i, v);
    }
    return true;
  }

  bool faces(const Plan& plan, const Element& e, Output& out) {
    const Property& list = e.properties[plan.indices];
    const std::int64_t vertices = out.vertex_count;
    // A triangle takes at least 8 bytes ("3 0 0 0\n"): reserve no more than the text can hold.
    out.mesh.triangles.reserve(std::min<std::size_t>(e.count, static_cast<std::size_t>(end_ - p_) / 8));
    Fan fan(out);
    for (std::size_t i = 0; i < e.count; ++i)
      for (const Property& p : e.properties) {
        if (&p != &list) {
          if (!any(p.type)) return false;
          continue;
        }
        std::int64_t n = 0;
        if (!integer(n) || n < 0 || !integer_in_range(*p.count_type, n)) return false;
        for (std::int64_t k = 0; k < n; ++k) {
          std::int64_t index = 0;
          if (!integer(index) || !integer_in_range(p.type, index) || index < 0 || index >= vertices)
            return false;
          fan.corner(static_cast<std::uint32_t>(index));
        }
        fan.end();
      }
    return true;
  }

  bool skip(const Element& e) {
    for (std::size_t i = 0; i < e.count; ++i)
      for (const Property& p : e.properties) {
        if (!p.count_type) {
          if (!any(p.type)) return false;
          continue;
        }
        std::int64_t n = 0;
        if (!integer(n) || !integer_in_range(*p.count_type, n) || n < 0) return false;
        for (std::int64_t k = 0; k < n; ++k)
          if (!any(p.type)) return false;
      }
    return true;
  }

private:
  const char* begin_;
  const char* p_;
  const char* end_;
};

// Every element in the file's order, its count first checked against the file's size as the validator
// does; `Reader` (Binary or Ascii) reads the vertices, the faces, or passes over another element.
template <class Reader>
bool read_elements(Reader& reader, const Header& header, const Plan& plan, std::size_t file_size,
                   Output& out) {
  for (const Element& e : header.elements) {
    if (!count_fits(e, header.encoding, file_size)) return false;
    if (e.properties.empty()) continue;
    const bool ok = &e == plan.vertex ? reader.vertices(plan, e, out)
                    : &e == plan.face ? reader.faces(plan, e, out)
                                      : reader.skip(e);
    if (!ok) return false;
  }
  return true;
}

} // namespace

std::optional<DirectRead> read_direct(const Header& header, std::string_view bytes) {
  const std::optional<Plan> plan = make_plan(header);
  if (!plan) return std::nullopt;
  Output out;
  out.vertex_count = static_cast<std::uint32_t>(plan->vertex->count);
  DirectRead result;
  if (header.encoding == Encoding::Ascii) {
    Ascii ascii(bytes, header.data_offset);
    if (!read_elements(ascii, header, *plan, bytes.size(), out)) return std::nullopt;
    if (const std::size_t next = ascii.next_token(); next < bytes.size()) {
      const auto lines = std::count(bytes.begin() + static_cast<std::ptrdiff_t>(header.data_offset),
                                    bytes.begin() + static_cast<std::ptrdiff_t>(next), '\n');
      result.trailing_line = header.data_line + static_cast<std::uint64_t>(lines);
    }
  } else {
    auto run = [&]<bool BigEndian>(Binary<BigEndian> binary) -> bool {
      if (!read_elements(binary, header, *plan, bytes.size(), out)) return false;
      result.data_end = binary.offset();
      return true;
    };
    const bool ok = header.encoding == Encoding::BinaryBigEndian
                        ? run(Binary<true>(bytes, header.data_offset))
                        : run(Binary<false>(bytes, header.data_offset));
    if (!ok) return std::nullopt;
  }
  result.mesh = std::move(out.mesh);
  result.short_faces = out.short_faces;
  return result;
}

} // namespace pdeface::ply::detail

// libFuzzer target for the .pdef decoder: whatever the bytes, decoding returns a face or an error (never a
// crash, a hang or an allocation the file's size does not justify); a face it returns can be described,
// meshed and encoded again, and encoding it gives a file that decodes to the same face within the error
// it was encoded with (exactly, for a lossless face).
//
// Every input is decoded twice: as it is, and repaired (its length field and checksum set to match), so
// that mutations reach the parser behind the checksum.

#include "pdeface/pdef/mesh.hpp"
#include "pdeface/pdef/pdef.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace {

namespace pdef = pdeface::pdef;

void one(std::string_view bytes) {
  pdeface::Result<pdef::Face> face = pdef::decode(bytes, "fuzz");
  if (!face) {
    if (!face.error().where.byte || *face.error().where.byte > bytes.size())
      throw std::logic_error("an error without its byte");
    return;
  }
  if (!pdef::sections(bytes, "fuzz")) throw std::logic_error("sections() refuses what decode() read");
  // A surface and a small mesh (may be refused: a hostile scheme or smoothing; must not crash).
  if (face->curve_count() * face->sample_count() <= 4096) (void)pdef::to_mesh(*face, pdef::Resolution{9, 9});
  if (face->residual && !face->residual->field.empty() &&
      face->residual->field.values.size() != face->residual->field.width * face->residual->field.height)
    throw std::logic_error("a residual layer's offsets do not fill its grid");
  if (face->residual && !face->residual->trimmed.empty() &&
      face->residual->trimmed.size() !=
          (face->residual->field.width - 1) * (face->residual->field.height - 1))
    throw std::logic_error("a residual layer's trim does not cover its grid's cells");
  // Encoding it again with an error its own grid satisfies: a file the encoder wrote keeps its grid and
  // decodes to the same values (tests/formats/pdef/golden_test.cpp); any other face (a hostile file whose
  // values the encoder would never write, e.g. heights' residuals far off their anchors) is encoded within
  // that error, as `encode` promises.
  // Faces of at most 4096 samples (real ones have 28 × 15-180): a larger hostile document's checks take
  // seconds under the sanitizers, within their bound (PdefHostile.LargeDocumentsAreEncodedWithin...).
  if (face->curve_count() * face->sample_count() > 4096) return;
  const double error = std::max(0.05, face->storage.step_mm);
  const pdeface::Result<pdef::Encoded> again =
      pdef::encode(*face, {.lossless = face->storage.lossless, .max_error_mm = error});
  if (again) {
    const pdeface::Result<pdef::Face> back = pdef::decode(again->bytes, "again");
    if (!back || back->filled != face->filled || back->pde.smoothing != face->pde.smoothing ||
        back->planes.size() != face->planes.size() || back->sample_count() != face->sample_count())
      throw std::logic_error("a decoded face does not survive encoding again");
    const double allowed = face->storage.lossless ? 0.0 : error;
    for (std::size_t j = 0; j < face->planes.size(); ++j)
      if (!(std::abs(back->planes[j] - face->planes[j]) <= allowed) ||
          !((back->curves.samples[j] - face->curves.samples[j]).rowwise().norm().maxCoeff() <= allowed))
        throw std::logic_error("a decoded face encoded again is not within the error it was encoded with");
  }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  one(bytes);
  if (size >= 14 && size < (std::size_t{1} << 26)) {
    std::string repaired(bytes);
    for (int i = 0; i < 4; ++i)
      repaired[6 + static_cast<std::size_t>(i)] = static_cast<char>(size >> (8 * i));
    const std::uint32_t crc = pdef::checksum(std::string_view(repaired).substr(0, size - 4));
    for (int i = 0; i < 4; ++i)
      repaired[size - 4 + static_cast<std::size_t>(i)] = static_cast<char>(crc >> (8 * i));
    one(repaired);
  }
  // A version 3 file: the curves' checksum (at the length the header states) repaired, so that mutations
  // of the residual layer after it reach its parser and the bit-plane decoder.
  if (size >= 18 && static_cast<std::uint8_t>(bytes[4]) == 3) {
    std::uint32_t length = 0;
    for (int i = 0; i < 4; ++i)
      length |= std::uint32_t{static_cast<std::uint8_t>(bytes[6 + static_cast<std::size_t>(i)])} << (8 * i);
    if (length >= 14 && length <= size) {
      std::string repaired(bytes);
      const std::uint32_t crc = pdef::checksum(std::string_view(repaired).substr(0, length - 4));
      for (int i = 0; i < 4; ++i)
        repaired[length - 4 + static_cast<std::size_t>(i)] = static_cast<char>(crc >> (8 * i));
      one(repaired);
    }
  }
  return 0;
}

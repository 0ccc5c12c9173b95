#pragma once
// The frame back to the scan as a document stores it: float64 (the matrix as it is) or float32 (a unit
// quaternion's x, y, z with w >= 0, the translation and the scale).

#include "bytes.hpp"

#include "pdeface/pdef/pdef.hpp"

namespace pdeface::pdef::detail {

void write_frame(Writer& w, const Frame& frame, bool float64);
//! The frame (units aside); failures recorded in `r`. `float64` says how it was stored.
[[nodiscard]] Frame read_frame(Reader& r, bool& float64);
//! The frame a decoder gets back from its float32 form.
[[nodiscard]] Frame as_float32(const Frame& frame);

} // namespace pdeface::pdef::detail

#pragma once
// The grid values that `Surface::evaluate(u_count, v_count)` and `GridMesher` share.

#include <cstddef>
#include <stdexcept>
#include <vector>

namespace pdeface::pde::detail {

//! `count` values spread evenly over [0, end], the last exactly `end`.
//! \throw std::invalid_argument for fewer than 2
[[nodiscard]] inline std::vector<double> spread(double end, std::size_t count) {
  if (count < 2) throw std::invalid_argument("pde: a grid needs at least 2 points each way");
  std::vector<double> values(count);
  for (std::size_t i = 0; i < count; ++i)
    values[i] = end * static_cast<double>(i) / static_cast<double>(count - 1);
  values.back() = end;
  return values;
}

} // namespace pdeface::pde::detail

#include "endatsim/checker/clock_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "endatsim/protocol/timing.hpp"

namespace endatsim::checker {

namespace {

// The sums of y_i and i * y_i over i = 0 .. m-1, in 64 bits when they cannot overflow there
// (edges in time order, the frame shorter than half a second), else in 128: the same values.
std::pair<__int128, __int128> sums_of(const std::vector<Time>& rising, std::size_t first, std::int64_t m) {
  const Time origin = rising[first];
  const std::int64_t span = (rising[first + static_cast<std::size_t>(m - 1)] - origin).count();
  if (span >= 0 && span < std::numeric_limits<std::int64_t>::max() / (m * m)) {
    std::int64_t sy = 0, sxy = 0;
    for (std::int64_t i = 0; i < m; ++i) {
      const std::int64_t y = (rising[first + static_cast<std::size_t>(i)] - origin).count();
      sy += y;
      sxy += i * y;
    }
    return {sy, sxy};
  }
  __int128 sy = 0, sxy = 0;
  for (std::int64_t i = 0; i < m; ++i) {
    const __int128 y = (rising[first + static_cast<std::size_t>(i)] - origin).count();
    sy += y;
    sxy += i * y;
  }
  return {sy, sxy};
}

}  // namespace

FittedFrequency fit_frequency(const std::vector<Time>& rising) {
  constexpr std::size_t kFirst = protocol::frame_position::edge_index(protocol::frame_position::kFirstSteadyRise);
  const std::int64_t m = std::min<std::int64_t>(static_cast<std::int64_t>(rising.size() - kFirst), kMaxFitEdges);
  if (m <= 0) return {};
  const Time origin = rising[kFirst];
  const auto y = [&](std::int64_t i) {
    return __int128{(rising[kFirst + static_cast<std::size_t>(i)] - origin).count()};
  };
  // x_i = i: its sums in closed form.
  const __int128 sx = __int128{m} * (m - 1) / 2;
  const __int128 sxx = __int128{m} * (m - 1) * (2 * m - 1) / 6;
  const auto [sy, sxy] = sums_of(rising, kFirst, m);
  FittedFrequency fit{m * sxy - sx * sy, m * sxx - sx * sx, 0};
  if (m < 3 || fit.num <= 0) return fit;
  // Residuals times den, exactly: den * y_i - (sy * sxx - sx * sxy) - i * num. A steady clock
  // (every simulated one) has none, and then no floating point is needed.
  const __int128 intercept = sy * sxx - sx * sxy;
  const auto residual = [&](std::int64_t i) { return fit.den * y(i) - intercept - i * fit.num; };
  std::int64_t i = 0;
  while (i < m && residual(i) == 0) ++i;
  if (i == m) return fit;
  long double squares = 0;
  for (i = 0; i < m; ++i) {
    const auto r = static_cast<long double>(residual(i)) / static_cast<long double>(fit.den);
    squares += r * r;
  }
  fit.uncertainty_ppm = uncertainty_ppm(fit, m, squares);
  return fit;
}

std::int64_t uncertainty_ppm(const FittedFrequency& fit, std::int64_t m, long double squares) {
  if (squares == 0) return 0;
  const long double slope_sd = std::sqrt(squares / static_cast<long double>(m - 2) /
                                         (static_cast<long double>(fit.den) / static_cast<long double>(m)));
  const long double period = static_cast<long double>(fit.num) / static_cast<long double>(fit.den);
  return static_cast<std::int64_t>(std::ceil(3 * slope_sd / period * 1e6L));
}

}  // namespace endatsim::checker

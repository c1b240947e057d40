#include "endatsim/checker/clock_fit.hpp"

#include <algorithm>
#include <cmath>

#include "endatsim/protocol/timing.hpp"

namespace endatsim::checker {

FittedFrequency fit_frequency(const std::vector<Time>& rising) {
  constexpr std::size_t kFirst = protocol::frame_position::edge_index(protocol::frame_position::kFirstSteadyRise);
  const std::int64_t m = std::min<std::int64_t>(static_cast<std::int64_t>(rising.size() - kFirst), kMaxFitEdges);
  const Time origin = rising[kFirst];
  const auto y = [&](std::int64_t i) { return __int128{(rising[kFirst + static_cast<std::size_t>(i)] - origin).count()}; };
  __int128 sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::int64_t i = 0; i < m; ++i) {
    sx += i;
    sy += y(i);
    sxx += __int128{i} * i;
    sxy += i * y(i);
  }
  FittedFrequency fit{m * sxy - sx * sy, m * sxx - sx * sx, 0};
  if (m < 3 || fit.num <= 0) return fit;
  // Residuals times den, exactly: den * y_i - (sy * sxx - sx * sxy) - i * num.
  const __int128 intercept = sy * sxx - sx * sxy;
  long double squares = 0;
  for (std::int64_t i = 0; i < m; ++i) {
    const auto r = static_cast<long double>(fit.den * y(i) - intercept - i * fit.num) / static_cast<long double>(fit.den);
    squares += r * r;
  }
  if (squares == 0) return fit;
  const long double slope_sd = std::sqrt(squares / static_cast<long double>(m - 2) /
                                         (static_cast<long double>(fit.den) / static_cast<long double>(m)));
  const long double period = static_cast<long double>(fit.num) / static_cast<long double>(fit.den);
  fit.uncertainty_ppm = static_cast<std::int64_t>(std::ceil(3 * slope_sd / period * 1e6L));
  return fit;
}


}  // namespace endatsim::checker

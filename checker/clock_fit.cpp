#include "endatsim/checker/clock_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
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

FittedFrequency fit_edges(const std::vector<Time>& rising);

// The rising edges without those of glitches. An edge of the clock has a period on each side, so
// its neighbours are two periods apart; a glitch's edge splits one period in two, so its
// neighbours are one period apart. The edge whose neighbours come nearest to one median period
// apart, within a quarter of it, is dropped, and again, until none is that near: one at a time,
// since dropping an edge moves its neighbours' (a glitch in each of two periods in a row leaves
// the clock's edge between them one period from each). None when no period is shorter than three
// quarters of the fit's (every steady or jittered clock: no median is then needed).
std::optional<std::vector<Time>> without_glitches(const std::vector<Time>& rising, const FittedFrequency& fit) {
  constexpr std::size_t kFirst = protocol::frame_position::edge_index(protocol::frame_position::kFirstSteadyRise);
  if (rising.size() < kFirst + 4) return std::nullopt;
  Time shortest = Time::max();
  for (std::size_t i = kFirst + 1; i < rising.size(); ++i) shortest = std::min(shortest, rising[i] - rising[i - 1]);
  if (__int128{shortest.count()} * 4 * fit.den >= 3 * fit.num) return std::nullopt;
  std::vector<Time> periods;
  for (std::size_t i = kFirst + 1; i < rising.size(); ++i) periods.push_back(rising[i] - rising[i - 1]);
  std::nth_element(periods.begin(), periods.begin() + static_cast<std::ptrdiff_t>(periods.size() / 2), periods.end());
  const Time median = periods[periods.size() / 2];
  std::vector<Time> kept = rising;
  while (kept.size() >= kFirst + 4) {
    std::size_t nearest = 0;
    Time off = Time::max();
    for (std::size_t i = kFirst + 1; i + 1 < kept.size(); ++i) {
      const Time joined = kept[i + 1] - kept[i - 1];
      const Time d = joined > median ? joined - median : median - joined;
      if (d < off) {
        off = d;
        nearest = i;
      }
    }
    if (off * 4 > median) break;
    kept.erase(kept.begin() + static_cast<std::ptrdiff_t>(nearest));
  }
  if (kept.size() == rising.size()) return std::nullopt;
  return kept;
}

}  // namespace

// A glitch on CLOCK (noise, a master's runt pulse) adds a rising edge that is no period of the
// clock: fitted with it, a 2 MHz frame came out at 2.07 MHz and was judged as a compensated one.
// The frame's frequency is fitted without such edges; the pulse-width rows judge the glitch.
FittedFrequency fit_frequency(const std::vector<Time>& rising) {
  const FittedFrequency fit = fit_edges(rising);
  if (fit.num <= 0) return fit;
  const auto steady = without_glitches(rising, fit);
  return steady ? fit_edges(*steady) : fit;
}

namespace {

FittedFrequency fit_edges(const std::vector<Time>& rising) {
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

}  // namespace

std::int64_t uncertainty_ppm(const FittedFrequency& fit, std::int64_t m, long double squares) {
  if (squares == 0) return 0;
  const long double slope_sd = std::sqrt(squares / static_cast<long double>(m - 2) /
                                         (static_cast<long double>(fit.den) / static_cast<long double>(m)));
  const long double period = static_cast<long double>(fit.num) / static_cast<long double>(fit.den);
  return static_cast<std::int64_t>(std::ceil(3 * slope_sd / period * 1e6L));
}

}  // namespace endatsim::checker

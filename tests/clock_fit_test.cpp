// fit_frequency against the least-squares fit written out plainly (every sum in 128 bits, every
// residual in long double, then the same uncertainty_ppm): the same period and the same
// uncertainty, bit for bit, for steady and jittered clocks, short frames and continuous clocks
// longer than the fit, and spans long enough to need the 128-bit sums.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "endatsim/checker/clock_fit.hpp"
#include "endatsim/protocol/timing.hpp"

namespace endatsim::checker {
namespace {

using sim::ps;

FittedFrequency plain_fit(const std::vector<Time>& rising) {
  constexpr std::size_t kFirst = protocol::frame_position::edge_index(protocol::frame_position::kFirstSteadyRise);
  const std::int64_t m = std::min<std::int64_t>(static_cast<std::int64_t>(rising.size() - kFirst), kMaxFitEdges);
  const auto y = [&](std::int64_t i) {
    return __int128{(rising[kFirst + static_cast<std::size_t>(i)] - rising[kFirst]).count()};
  };
  __int128 sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::int64_t i = 0; i < m; ++i) {
    sx += i;
    sy += y(i);
    sxx += __int128{i} * i;
    sxy += i * y(i);
  }
  FittedFrequency fit{m * sxy - sx * sy, m * sxx - sx * sx, 0};
  if (m < 3 || fit.num <= 0) return fit;
  const __int128 intercept = sy * sxx - sx * sxy;
  long double squares = 0;
  for (std::int64_t i = 0; i < m; ++i) {
    const auto r =
        static_cast<long double>(fit.den * y(i) - intercept - i * fit.num) / static_cast<long double>(fit.den);
    squares += r * r;
  }
  fit.uncertainty_ppm = uncertainty_ppm(fit, m, squares);
  return fit;
}

std::vector<Time> edges(std::mt19937_64& rng, std::size_t n, std::int64_t period, std::int64_t jitter) {
  std::uniform_int_distribution<std::int64_t> wobble(-jitter, jitter);
  std::vector<Time> rising;
  std::int64_t t = 1'000'000;
  for (std::size_t k = 0; k < n; ++k) {
    rising.push_back(ps(t + (k == 0 ? 0 : wobble(rng))));
    t += period;
  }
  return rising;
}

void expect_same(const std::vector<Time>& rising, const std::string& what) {
  const FittedFrequency fast = fit_frequency(rising);
  const FittedFrequency plain = plain_fit(rising);
  EXPECT_TRUE(fast.num == plain.num) << what;
  EXPECT_TRUE(fast.den == plain.den) << what;
  EXPECT_EQ(fast.uncertainty_ppm, plain.uncertainty_ppm) << what;
}

TEST(ClockFit, FitsLikeThePlainLeastSquaresForSteadyAndJitteredClocks) {
  std::mt19937_64 rng(17);
  std::size_t jittered = 0;
  for (int run = 0; run < 400; ++run) {
    const std::size_t n = std::uniform_int_distribution<std::size_t>(3, 5000)(rng);
    const std::int64_t period = std::uniform_int_distribution<std::int64_t>(62'500, 10'000'000)(rng);
    const std::int64_t jitter = run % 2 == 0 ? 0 : std::uniform_int_distribution<std::int64_t>(1, period / 20)(rng);
    const auto rising = edges(rng, n, period, jitter);
    expect_same(rising, "run " + std::to_string(run));
    if (fit_frequency(rising).uncertainty_ppm > 0) ++jittered;
  }
  EXPECT_GT(jittered, 100U);  // the floating-point path ran, not only the steady one
}

TEST(ClockFit, FitsLikeThePlainLeastSquaresOverSpansThatNeedTheWideSums) {
  std::mt19937_64 rng(29);
  // 4 096 edges 1 ms apart: 4 s, past the 64-bit sums' bound; and 1 s with a few edges.
  for (const auto& [n, period] :
       {std::pair<std::size_t, std::int64_t>{4097, 1'000'000'000}, {5, 250'000'000'000}, {40, 30'000'000'000}}) {
    for (const std::int64_t jitter : {std::int64_t{0}, period / 1000}) {
      const auto rising = edges(rng, n, period, jitter);
      expect_same(rising, std::to_string(n) + " edges of " + std::to_string(period) + " ps");
    }
  }
}

TEST(ClockFit, ASteadyClockHasNoUncertaintyAndItsExactPeriod) {
  std::mt19937_64 rng(1);
  const FittedFrequency fit = fit_frequency(edges(rng, 160, 62'500, 0));
  EXPECT_EQ(fit.uncertainty_ppm, 0);
  EXPECT_TRUE(fit.num == 62'500 * fit.den);
  EXPECT_EQ(fit.hertz(), 16'000'000);
}

// A glitch on CLOCK adds a rising edge inside a period: 10 ns LOW 100 ns after RE20, or 10 ns HIGH
// in a LOW phase. Fitted with it, a 2 MHz frame came out at 2.07 MHz, above the bound without
// compensation. Without it, the fit is the steady clock's, exactly. A jittered clock (every
// period within 10 %) keeps all its edges.
TEST(ClockFit, AGlitchsRisingEdgeIsLeftOutOfTheFit) {
  std::mt19937_64 rng(3);
  const auto rising = edges(rng, 44, 500'000, 0);
  const FittedFrequency steady = fit_frequency(rising);
  for (const std::int64_t into : {110'000, 260'000, 400'000}) {
    auto glitched = rising;
    glitched.insert(glitched.begin() + 20, rising[19] + ps(into));
    EXPECT_GT(plain_fit(glitched).hertz(), 2'000'000) << into;  // fitted with the glitch's edge
    const FittedFrequency fit = fit_frequency(glitched);
    EXPECT_TRUE(fit.num == steady.num && fit.den == steady.den) << into;
    EXPECT_EQ(fit.hertz(), 2'000'000) << into;
    EXPECT_EQ(fit.uncertainty_ppm, 0) << into;
  }
  // A glitch at the same place in two or three periods in a row (crosstalk from DATA, which
  // changes 60 ns after each rising edge): the clock's edges between them are one period from
  // each glitch, as the glitches are from theirs; dropped one at a time, the glitches go and the
  // clock's edges stay. (Before, ties kept all of them: 2.07 MHz.)
  for (const int glitches : {2, 3}) {
    std::vector<Time> glitched;
    for (std::size_t k = 0; k < rising.size(); ++k) {
      glitched.push_back(rising[k]);
      if (k >= 19 && k < 19 + static_cast<std::size_t>(glitches)) glitched.push_back(rising[k] + ps(60'000));
    }
    EXPECT_GT(plain_fit(glitched).hertz(), 2'000'000) << glitches;
    const FittedFrequency fit = fit_frequency(glitched);
    EXPECT_TRUE(fit.num == steady.num && fit.den == steady.den) << glitches;
  }
  for (int run = 0; run < 50; ++run) {
    const auto jittered = edges(rng, 44, 500'000, 25'000);
    expect_same(jittered, "jittered " + std::to_string(run));
  }
}

TEST(ClockFit, TooFewEdgesGiveNoPeriod) {
  EXPECT_TRUE(fit_frequency({}).num == 0);
  EXPECT_TRUE(fit_frequency({ps(1)}).num == 0);
  EXPECT_TRUE(fit_frequency({ps(1), ps(2)}).num <= 0);
}

}  // namespace
}  // namespace endatsim::checker

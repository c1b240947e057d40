// The clock frequency of a frame, fitted over its rising edges (clock_fit.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include "endatsim/sim/int128.hpp"
#include "endatsim/sim/time.hpp"

namespace endatsim::checker {

using sim::Time;

// The frame's clock frequency from a least-squares fit over its rising edges from RE2 on (the
// first period contains t_ST), at most kMaxFitEdges of them (a long continuous clock). A steady
// clock is judged exactly; with jitter the limits widen by three standard errors of the fit,
// so that a clock whose frequency is right is not flagged for the scatter of its edges. The rising
// edges of glitches (an edge that splits one period of the median in two) are left out of the fit.
constexpr std::int64_t kMaxFitEdges = 4096;

struct FittedFrequency {
  sim::Int128 num = 0;  // period = num / den [ps]; f = 1e12 * den / num [Hz]
  sim::Int128 den = 0;
  std::int64_t uncertainty_ppm = 0;
  sim::Hertz hertz() const { return static_cast<sim::Hertz>((sim::Int128{sim::kPsPerSecond} * den + num / 2) / num); }
  // f above (or below) bound by more than `ppm` parts per million plus the fit's uncertainty.
  bool above(sim::Hertz bound, std::int64_t ppm) const {
    return sim::Int128{sim::kPsPerSecond} * den * 1'000'000 >
           sim::Int128{bound} * (1'000'000 + ppm + uncertainty_ppm) * num;
  }
  // The period shorter than `min` by more than `ppm` plus the fit's uncertainty.
  bool period_below(sim::Time min, std::int64_t ppm) const {
    return num * 1'000'000 < sim::Int128{min.count()} * den * (1'000'000 - ppm - uncertainty_ppm);
  }
  bool below(sim::Hertz bound, std::int64_t ppm) const {
    return sim::Int128{sim::kPsPerSecond} * den * 1'000'000 <
           sim::Int128{bound} * (1'000'000 - ppm - uncertainty_ppm) * num;
  }
};

FittedFrequency fit_frequency(const std::vector<Time>& rising);
// Three standard errors of the fitted slope, in ppm of the period (rounded up), from the sum of
// the squared residuals of `m` edges (in ps^2); 0 when they are all zero.
std::int64_t uncertainty_ppm(const FittedFrequency& fit, std::int64_t m, long double squares);

}  // namespace endatsim::checker

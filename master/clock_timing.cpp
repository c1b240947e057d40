#include "endatsim/master/clock_timing.hpp"

#include <algorithm>

#include <boost/random/uniform_int_distribution.hpp>

#include "endatsim/protocol/timing.hpp"

namespace endatsim::master {

void ClockTiming::begin(sim::Hertz f_c, sim::Time now) {
  const sim::Time period = sim::period_of(f_c);
  high_ = period * params_.high_permille / 1000;
  low_ = period - high_;
  nominal_ = now;
}

sim::Time ClockTiming::after_falling(unsigned clock, sim::Time now) {
  // 2.3.2 note 8: the first LOW phase is stretched to t_ST.
  nominal_ += clock == protocol::frame_position::kFrameStart ? std::max(low_, params_.t_st) : low_;
  return jittered(now);
}

sim::Time ClockTiming::after_rising(sim::Time now) {
  nominal_ += high_;
  return jittered(now);
}

sim::Time ClockTiming::jittered(sim::Time now) {
  if (params_.jitter == sim::Time::zero()) return nominal_;
  boost::random::uniform_int_distribution<std::int64_t> d(-params_.jitter.count(), params_.jitter.count());
  return std::max(now, nominal_ + sim::Time{d(rng_)});
}

}  // namespace endatsim::master

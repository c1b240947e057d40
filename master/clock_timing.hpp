// When the master's CLOCK edges of a frame are due (D297403 2.3.2): HIGH and LOW phases from f_c
// and the duty cycle, the first LOW phase stretched to t_ST (note 8), and the scenario's jitter
// added to each edge around its nominal time, so that jitter does not accumulate. The frame
// engine (frame_engine.hpp) drives the edges; the random generator also draws the delay
// counter's phase (2.1.2), in the order the frame asks for them, so a seed replays a run.
#pragma once

#include <algorithm>
#include <cstdint>

#include <boost/random/mersenne_twister.hpp>
#include <boost/random/uniform_int_distribution.hpp>

#include "endatsim/master/master_params.hpp"
#include "endatsim/protocol/timing.hpp"
#include "endatsim/sim/time.hpp"

namespace endatsim::master {

class ClockTiming {
 public:
  explicit ClockTiming(const MasterParams& params) : params_(params), rng_(params.seed) {}

  // A frame at `f_c` begins at `now` (its first falling edge, FE1).
  void begin(sim::Hertz f_c, sim::Time now);
  sim::Time high() const { return high_; }
  sim::Time low() const { return low_; }
  // When the rising edge after falling edge FE`clock` is due, seen at that falling edge (`now`).
  // Inline, as the edges' own work: they run on every clock edge.
  sim::Time after_falling(unsigned clock, sim::Time now) {
    // 2.3.2 note 8: the first LOW phase is stretched to t_ST.
    nominal_ += clock == protocol::frame_position::kFrameStart ? std::max(low_, params_.t_st) : low_;
    return jittered(now);
  }
  // When the falling edge after a rising edge is due, seen at that rising edge (`now`).
  sim::Time after_rising(sim::Time now) {
    nominal_ += high_;
    return jittered(now);
  }
  boost::random::mt19937_64& rng() { return rng_; }

 private:
  sim::Time jittered(sim::Time now) {
    if (params_.jitter == sim::Time::zero()) return nominal_;
    boost::random::uniform_int_distribution<std::int64_t> d(-params_.jitter.count(), params_.jitter.count());
    return std::max(now, nominal_ + sim::Time{d(rng_)});
  }

  const MasterParams& params_;
  boost::random::mt19937_64 rng_;
  sim::Time high_{0}, low_{0};
  sim::Time nominal_{0};  // the current edge without jitter
};

}  // namespace endatsim::master

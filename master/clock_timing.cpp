#include "endatsim/master/clock_timing.hpp"

namespace endatsim::master {

void ClockTiming::begin(sim::Hertz f_c, sim::Time now) {
  const sim::Time period = sim::period_of(f_c);
  high_ = period * params_.high_permille / 1000;
  low_ = period - high_;
  nominal_ = now;
}

}  // namespace endatsim::master

// A measured duration against a limit when each edge is known only to within `resolution`: a
// logic analyzer samples every period r, so an edge it shows happened up to r earlier, and a
// duration between two edges is true to within (-r, +r). A limit inside that interval can be
// neither passed nor failed: it is undecided at this resolution. A resolution of 0 means exact
// event times (a simulator's own, or the VCD of one).
#pragma once

#include <cstdint>

#include "sim/time.hpp"

namespace endatsim::checker {

enum class Decision : std::uint8_t { Pass, Fail, Undecided };

// measured >= min
constexpr Decision at_least(sim::Time measured, sim::Time min, sim::Time resolution) {
  if (resolution == sim::Time::zero()) return measured >= min ? Decision::Pass : Decision::Fail;
  if (measured - resolution >= min) return Decision::Pass;
  if (measured + resolution <= min) return Decision::Fail;
  return Decision::Undecided;
}

// measured > min
constexpr Decision more_than(sim::Time measured, sim::Time min, sim::Time resolution) {
  if (resolution == sim::Time::zero()) return measured > min ? Decision::Pass : Decision::Fail;
  return at_least(measured, min, resolution);
}

// measured <= max
constexpr Decision at_most(sim::Time measured, sim::Time max, sim::Time resolution) {
  if (resolution == sim::Time::zero()) return measured <= max ? Decision::Pass : Decision::Fail;
  if (measured + resolution <= max) return Decision::Pass;
  if (measured - resolution >= max) return Decision::Fail;
  return Decision::Undecided;
}

}  // namespace endatsim::checker

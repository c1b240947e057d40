// A measured duration against a limit when each edge is known only to within `resolution`: a
// logic analyzer samples every period r, so an edge it shows happened up to r earlier, and a
// duration between two edges is true to within (-r, +r). A limit inside that interval can be
// neither passed nor failed: it is undecided at this resolution. A resolution of 0 means exact
// event times (a simulator's own, or the VCD of one).
#pragma once

#include <cstdint>

#include "endatsim/sim/time.hpp"

namespace endatsim::checker {

enum class Decision : std::uint8_t { Pass, Fail, Undecided };

enum class Bound : std::uint8_t { AtLeast, MoreThan, AtMost };

// A decision with what it was made from, so that the conformance table can show the worst
// measured value of a row and its margin to the limit also when every occasion passed.
struct Judgement {
  Decision decision = Decision::Pass;
  sim::Time measured{0};
  sim::Time limit{0};
  Bound bound = Bound::AtLeast;
  constexpr operator Decision() const { return decision; }  // NOLINT: a judgement is read as its decision
  // How far inside the limit the measured value lies; negative outside it.
  constexpr sim::Time margin() const { return bound == Bound::AtMost ? limit - measured : measured - limit; }
};

// measured >= min
constexpr Judgement at_least(sim::Time measured, sim::Time min, sim::Time resolution) {
  const auto judged = [&](Decision d) { return Judgement{d, measured, min, Bound::AtLeast}; };
  if (resolution == sim::Time::zero()) return judged(measured >= min ? Decision::Pass : Decision::Fail);
  if (measured - resolution >= min) return judged(Decision::Pass);
  if (measured + resolution <= min) return judged(Decision::Fail);
  return judged(Decision::Undecided);
}

// measured > min
constexpr Judgement more_than(sim::Time measured, sim::Time min, sim::Time resolution) {
  Judgement j = at_least(measured, min, resolution);
  if (resolution == sim::Time::zero()) j.decision = measured > min ? Decision::Pass : Decision::Fail;
  j.bound = Bound::MoreThan;
  return j;
}

// measured <= max
constexpr Judgement at_most(sim::Time measured, sim::Time max, sim::Time resolution) {
  const auto judged = [&](Decision d) { return Judgement{d, measured, max, Bound::AtMost}; };
  if (resolution == sim::Time::zero()) return judged(measured <= max ? Decision::Pass : Decision::Fail);
  if (measured + resolution <= max) return judged(Decision::Pass);
  if (measured - resolution >= max) return judged(Decision::Fail);
  return judged(Decision::Undecided);
}

}  // namespace endatsim::checker

#pragma once
// master/pacing.hpp — when the master's next frame may start: on the cycle its operation asks
// for (a control loop's read cycle; 0 = at once), and not before the encoder is ready again
// after the last frame (t_m and t_R, D297403 2.3.2; the wait after an error handling, A2; after
// "Encoder receive reset", 2.7; t3 after the power-on pulse, 2.3.3). Counts the read cycles the
// waits made late.

#include <algorithm>
#include <cstdint>

#include "endatsim/sim/time.hpp"

namespace endatsim::master {

class Pacing {
 public:
  using Time = sim::Time;

  // An operation's first frame is due at `begin`.
  void start(Time begin) { next_due_ = begin; }
  // Its next frame is due `cycle` after the last one was; `read_cycle`: the cycle of a control
  // loop, which counts as overrun when the encoder is not ready by then.
  void next_cycle(Time cycle, bool read_cycle) {
    next_due_ += cycle;
    if (read_cycle && ready_at_ > next_due_) ++cycle_overruns_;
  }
  // The encoder is ready again at `t` (set after each frame), or not before `t` (a longer wait).
  void ready_at(Time t) { ready_at_ = t; }
  void not_before(Time t) { ready_at_ = std::max(ready_at_, t); }

  // When the next frame starts: due and the encoder ready.
  Time due() const { return std::max(next_due_, ready_at_); }
  Time ready_at() const { return ready_at_; }
  std::uint64_t cycle_overruns() const { return cycle_overruns_; }

 private:
  Time next_due_{0};
  Time ready_at_{0};
  std::uint64_t cycle_overruns_ = 0;
};

}  // namespace endatsim::master

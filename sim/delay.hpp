// A transport delay from one signal to another: every committed change of `in` appears on
// `out` after the delay for that direction (rise: 0 -> 1, fall: 1 -> 0). The delay can be
// changed while running (cable swap); changes already in flight keep their old delay.
//
// Each change in flight is one entry in the kernel's queue, taken in the order of the moment it
// went in: with unequal rise and fall delays a later change may overtake an earlier one, and the
// kernel's (time, sequence) order delivers them as a transport delay must. The timing wheel
// (event_queue.hpp) holds the dozen edges a long cable keeps in flight at no extra cost.
#pragma once

#include "endatsim/sim/signal.hpp"

namespace endatsim::sim {

class TransportDelay {
 public:
  TransportDelay(Kernel& kernel, Signal& in, Signal& out, Time rise, Time fall)
      : kernel_(kernel), out_(out), rise_(rise), fall_(fall) {
    in.on_change(bind<&TransportDelay::on_input>(this));
  }
  TransportDelay(Kernel& kernel, Signal& in, Signal& out, Time delay)
      : TransportDelay(kernel, in, out, delay, delay) {}
  TransportDelay(const TransportDelay&) = delete;
  TransportDelay& operator=(const TransportDelay&) = delete;

  void set_delays(Time rise, Time fall) { rise_ = rise; fall_ = fall; }
  Time rise() const { return rise_; }
  Time fall() const { return fall_; }

 private:
  void on_input(std::uint64_t value) {
    // A zero delay wakes up in the next delta cycle, like any zero-delay wake-up.
    kernel_.schedule(value != 0 ? rise_ : fall_, Action{&Kernel::write_signal, &out_, value});
  }

  Kernel& kernel_;
  Signal& out_;
  Time rise_;
  Time fall_;
};

}  // namespace endatsim::sim

// A transport delay from one signal to another: every committed change of `in` appears on
// `out` after the delay for that direction (rise: 0 -> 1, fall: 1 -> 0). The delay can be
// changed while running (cable swap); changes already in flight keep their old delay.
#pragma once

#include "sim/signal.hpp"

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
    kernel_.schedule(value ? rise_ : fall_, bind<&TransportDelay::deliver>(this, value));
  }
  void deliver(std::uint64_t value) { out_.write(value != 0); }

  Kernel& kernel_;
  Signal& out_;
  Time rise_;
  Time fall_;
};

}  // namespace endatsim::sim

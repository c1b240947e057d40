// A transport delay from one signal to another: every committed change of `in` appears on
// `out` after the delay for that direction (rise: 0 -> 1, fall: 1 -> 0). The delay can be
// changed while running (cable swap); changes already in flight keep their old delay.
//
// A long cable at a high clock rate holds a dozen edges in flight. They wait in this line's own
// queue, and only the earliest is in the kernel's queue, ordered as if it had been scheduled
// when the edge went in (Kernel::take_seq): the same result as one kernel entry per edge.
#pragma once

#include <vector>

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
  struct InFlight {
    Time when;
    std::uint64_t seq;
    bool value;
    bool before(const InFlight& o) const { return when != o.when ? when < o.when : seq < o.seq; }
  };
  void on_input(std::uint64_t value);
  static void deliver(void* self, std::uint64_t entry);
  void queue_front();

  Kernel& kernel_;
  Signal& out_;
  Time rise_;
  Time fall_;
  std::vector<InFlight> in_flight_;  // in delivery order from head_ on
  std::size_t head_ = 0;
  std::uint64_t entry_ = 0;  // the kernel entry for the front; older ones are stale
};

}  // namespace endatsim::sim

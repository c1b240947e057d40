#pragma once
// slave/readiness.hpp — whether the encoder takes a clock edge: not while it runs up after
// switching on or a reset, with DATA high-impedance (D297403 2.3.3), nor within t_R of its last
// frame's end (2.3.2); and how many position answers after start-up still carry an unsettled
// value (a fault, EncoderParams::unsettled_positions).

#include <cstdint>

#include "endatsim/sim/kernel.hpp"

namespace endatsim::slave {

using sim::Time;

class Readiness {
 public:
  // `started` runs when a run-up ends.
  Readiness(sim::Kernel& kernel, sim::Action started, unsigned unsettled_positions);
  Readiness(const Readiness&) = delete;
  Readiness& operator=(const Readiness&) = delete;

  void run_up(Time duration);
  bool running_up() const { return running_up_; }
  void frame_ended(Time t_r) { ready_at_ = kernel_.now() + t_r; }
  // Whether the encoder takes an edge now; one it does not take is counted.
  bool takes_edge() {
    if (!running_up_ && kernel_.now() >= ready_at_) return true;
    ++ignored_edges_;
    return false;
  }
  std::uint64_t ignored_edges() const { return ignored_edges_; }

  // After start-up: this many position answers carry an unsettled value.
  void restart_settling(unsigned unsettled_positions) { unsettled_left_ = unsettled_positions; }
  bool settled() const { return unsettled_left_ == 0; }
  // Whether this position answer carries one.
  bool take_unsettled() {
    if (unsettled_left_ == 0) return false;
    --unsettled_left_;
    return true;
  }

 private:
  void on_run_up_done();

  sim::Kernel& kernel_;
  sim::Action started_;
  sim::Timer run_up_timer_;
  bool running_up_ = false;
  Time ready_at_{0};
  unsigned unsettled_left_;
  std::uint64_t ignored_edges_ = 0;
};

}  // namespace endatsim::slave

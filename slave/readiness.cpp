#include "endatsim/slave/readiness.hpp"

namespace endatsim::slave {

Readiness::Readiness(sim::Kernel& kernel, sim::Action started, unsigned unsettled_positions)
    : kernel_(kernel),
      started_(started),
      run_up_timer_(kernel, sim::bind<&Readiness::on_run_up_done>(this)),
      unsettled_left_(unsettled_positions) {}

void Readiness::run_up(Time duration) {
  running_up_ = true;
  run_up_timer_.start(duration);
}

void Readiness::on_run_up_done() {
  running_up_ = false;
  started_();
}

}  // namespace endatsim::slave

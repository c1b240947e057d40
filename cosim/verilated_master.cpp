#include "endatsim/cosim/verilated_master.hpp"

#include <stdexcept>
#include <utility>

namespace endatsim::cosim {

VerilatedMaster::VerilatedMaster(Bench& bench, VerilatedPorts ports, std::function<void()> eval, Time sys_clock_period)
    : bench_(bench), ports_(std::move(ports)), eval_(std::move(eval)), half_period_(sys_clock_period / 2) {
  if (ports_.sys_clk == nullptr || ports_.clock == nullptr || ports_.data_out == nullptr || ports_.data_in == nullptr)
    throw std::invalid_argument("VerilatedMaster: sys_clk, clock, data_out and data_in are needed");
  if (sys_clock_period <= Time::zero() || sys_clock_period.count() % 2 != 0)
    throw std::invalid_argument("VerilatedMaster: the system clock's period must be an even number of picoseconds, got " +
                                sim::format_time(sys_clock_period));
  if (static_cast<bool>(ports_.position) != static_cast<bool>(ports_.position_valid) ||
      static_cast<bool>(ports_.parameter) != static_cast<bool>(ports_.parameter_valid))
    throw std::invalid_argument("VerilatedMaster: a reported value and its strobe go together");
  *ports_.sys_clk = 0;
  *ports_.data_in = bench_.data_in() ? 1 : 0;
  eval_();
  push_outputs();
}

void VerilatedMaster::half_cycle() {
  bench_.advance_to(bench_.now() + half_period_);
  // DATA as the line delivers it up to and including this edge: an RTL master's synchronizer
  // takes it on this edge, as in an HDL simulator where the change comes first.
  *ports_.data_in = bench_.data_in() ? 1 : 0;
  *ports_.sys_clk = *ports_.sys_clk != 0 ? 0 : 1;
  eval_();
  push_outputs();
  if (*ports_.sys_clk != 0) {
    ++cycles_;
    read_reports();
  }
}

// The master's pins onto the line, only where they changed; DATA's level before its enable, so
// that a driver turned on drives the new level from its first instant.
void VerilatedMaster::push_outputs() {
  const auto drive = [&](int& last, int now, MasterPin pin) {
    if (now == last) return;
    last = now;
    bench_.drive(pin, now != 0);
  };
  drive(clock_, *ports_.clock != 0 ? 1 : 0, MasterPin::Clock);
  drive(data_out_, *ports_.data_out != 0 ? 1 : 0, MasterPin::DataOut);
  const bool enabled = ports_.data_enable == nullptr || ((*ports_.data_enable != 0) != ports_.enable_active_low);
  drive(enable_, enabled ? 1 : 0, MasterPin::DataEnable);
}

void VerilatedMaster::read_reports() {
  if (ports_.position_valid && ports_.position_valid()) bench_.report_position(ports_.position());
  if (ports_.parameter_valid && ports_.parameter_valid())
    bench_.report_parameter(static_cast<std::uint16_t>(ports_.parameter()));
}

bool VerilatedMaster::run_cycles(std::uint64_t cycles) {
  for (std::uint64_t i = 0; i < 2 * cycles; ++i) {
    if (bench_.should_stop()) return false;
    half_cycle();
  }
  return true;
}

bool VerilatedMaster::run_until(const std::function<bool()>& done) {
  while (!bench_.should_stop()) {
    half_cycle();
    if (*ports_.sys_clk != 0 && done()) return true;
  }
  return false;
}

bool VerilatedMaster::run_for(Time span) {
  const Time end = bench_.now() + span;
  while (bench_.now() + half_period_ <= end) {
    if (bench_.should_stop()) return false;
    half_cycle();
  }
  return true;
}

}  // namespace endatsim::cosim

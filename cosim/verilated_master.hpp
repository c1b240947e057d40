// A Verilated HDL master (Verilator's C++ model of the user's RTL) stepped on its own system
// clock inside the bench: at each edge of that clock the bench runs up to the edge, DATA at the
// master's receiver is put on the model's data_in, the model is evaluated, and whatever it now
// drives on CLOCK and DATA goes onto the line at that instant. Nothing here includes Verilator's
// headers: the model's 1-bit ports are the CData (unsigned char) members Verilator generates,
// wider ones are read through small functions, so the adapter builds without Verilator.
#pragma once

#include <cstdint>
#include <functional>

#include "endatsim/cosim/bench.hpp"

namespace endatsim::cosim {

struct VerilatedPorts {
  unsigned char* sys_clk = nullptr;      // in: the master's system clock, driven by the adapter
  unsigned char* clock = nullptr;        // out: EnDat CLOCK
  unsigned char* data_out = nullptr;     // out: DATA driver input
  unsigned char* data_enable = nullptr;  // out: DATA driver enable (null: always driving)
  bool enable_active_low = false;
  unsigned char* data_in = nullptr;      // in: DATA at the master's receiver
  // What the master decoded, read at each rising system clock edge while the strobe is HIGH.
  std::function<bool()> position_valid;
  std::function<std::uint64_t()> position;
  std::function<bool()> parameter_valid;
  std::function<std::uint64_t()> parameter;
};

class VerilatedMaster {
 public:
  // `eval`: the model's eval(); `sys_clock_period`: an even number of picoseconds. Throws
  // std::invalid_argument for a missing port or an odd period.
  VerilatedMaster(Bench& bench, VerilatedPorts ports, std::function<void()> eval, Time sys_clock_period);

  // Whole system clock cycles: for `cycles`, until `done` holds at a rising edge, or for `span`.
  // Each stops early at the bench's max_time; they return false then.
  bool run_cycles(std::uint64_t cycles);
  bool run_until(const std::function<bool()>& done);
  bool run_for(Time span);

  std::uint64_t cycles() const { return cycles_; }

 private:
  void half_cycle();
  void push_outputs();
  void read_reports();

  Bench& bench_;
  VerilatedPorts ports_;
  std::function<void()> eval_;
  Time half_period_;
  std::uint64_t cycles_ = 0;
  int clock_ = -1, data_out_ = -1, enable_ = -1;  // as last driven onto the line; -1: not yet
};

}  // namespace endatsim::cosim

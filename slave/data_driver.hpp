#pragma once
// slave/data_driver.hpp — the encoder's end of the DATA pair: the level its logic sends and
// whether its RS-485 driver is on (D297403 2.3: the encoder drives DATA LOW when idle and hands
// the line to the master for mode commands and supplements; 2.10: a driver at high impedance
// keeps off the line). Both reach the pins after the encoder's output delay (its share of t_D).

#include "endatsim/line/line.hpp"
#include "endatsim/sim/kernel.hpp"

namespace endatsim::slave {

class DataDriver {
 public:
  DataDriver(sim::Kernel& kernel, line::Line::EncoderSide pins, sim::Time output_delay);
  DataDriver(const DataDriver&) = delete;
  DataDriver& operator=(const DataDriver&) = delete;

  void drive(bool level) { level_.write(level); }
  // The driver on (`on`) or at high impedance; release() hands DATA to the master.
  void enable(bool on) { enabled_.write(on); }
  void release() { enabled_.write(false); }

 private:
  sim::Signal level_;
  sim::Signal enabled_;
  sim::TransportDelay level_delay_;
  sim::TransportDelay enabled_delay_;
};

}  // namespace endatsim::slave

// Helpers shared by the tests: a scripted clock/data driver on the master side of a line,
// so that the encoder can be tested without the master model.
#pragma once

#include <string>
#include <vector>

#include "line/line.hpp"

namespace endatsim::test_support {

// Drives CLOCK at a fixed period starting at `start` (FE1), sends a dummy 0 and six mode
// bits on FE2..FE8 like a master (spec 2.3), releases DATA at FE9, and gives `clocks` pulses.
class ScriptedClock {
 public:
  ScriptedClock(sim::Kernel& k, line::Line& line, sim::Time period, unsigned clocks, std::uint8_t mode_bits,
                sim::Time start = sim::Time::zero(), bool drive_data = true)
      : k_(k), m_(line.master()), half_(period / 2), clocks_(clocks), mode_(mode_bits), drive_data_(drive_data),
        timer_(k, sim::bind<&ScriptedClock::edge>(this)) {
    timer_.start(start - k.now());
  }
  const std::vector<sim::Time>& rising() const { return rising_; }

 private:
  void edge() {
    if (low_) {
      low_ = false;
      m_.clock_out.write(true);
      rising_.push_back(k_.now());
      if (clock_ < clocks_) timer_.start(half_);
      return;
    }
    low_ = true;
    ++clock_;
    m_.clock_out.write(false);
    if (clock_ == 2) {
      m_.data_enable.write(drive_data_);
      m_.data_out.write(false);
    } else if (clock_ >= 3 && clock_ <= 8) {
      m_.data_out.write(((mode_ >> (8 - clock_)) & 1U) != 0);
    } else if (clock_ == 9) {
      m_.data_enable.write(false);
    }
    timer_.start(half_);
  }

  sim::Kernel& k_;
  line::Line::MasterSide m_;
  sim::Time half_;
  unsigned clocks_;
  std::uint8_t mode_;
  bool drive_data_;
  sim::Timer timer_;
  unsigned clock_ = 0;
  bool low_ = false;
  std::vector<sim::Time> rising_;
};

// Records DATA at the encoder's pins at each falling CLOCK edge there: entry k-1 is the bit
// the encoder put out after RE_(k-1), i.e. slot k-1 (entry 0 is taken at FE1).
class PinSampler {
 public:
  PinSampler(sim::Kernel&, line::Line& line) : pins_(line.pins(line::ObservationPoint::EncoderPins)) {
    pins_.clock.on_change(sim::bind<&PinSampler::on_clock>(this));
  }
  // Bits of slots first..last (inclusive) as a string of '0'/'1'.
  std::string slots(unsigned first, unsigned last) const {
    std::string s;
    for (unsigned k = first; k <= last && k < samples_.size(); ++k) s += samples_[k] ? '1' : '0';
    return s;
  }

 private:
  void on_clock(std::uint64_t level) {
    if (level == 0) samples_.push_back(pins_.data.read());
  }
  line::Line::Pins pins_;
  std::vector<bool> samples_;
};

}  // namespace endatsim::test_support

// Helpers shared by the tests: a scripted clock/data driver on the master side of a line,
// so that the encoder can be tested without the master model.
#pragma once

#include <algorithm>
#include <iterator>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "endatsim/line/line.hpp"

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

// A hand-written master for one frame: CLOCK at a fixed period from `start` (FE1) for `clocks`
// pulses, and on each falling edge FE_k the DATA driver does what drive[k-1] says: '0'/'1'
// drive that level, anything else releases the line. Sequences in the tests are written out
// from the spec, independently of the master model.
class ScriptedFrame {
 public:
  ScriptedFrame(sim::Kernel& k, line::Line& line, sim::Time period, unsigned clocks, std::string drive,
                sim::Time start = sim::Time::zero())
      : m_(line.master()), half_(period / 2), clocks_(clocks), drive_(std::move(drive)),
        timer_(k, sim::bind<&ScriptedFrame::edge>(this)) {
    timer_.start(start - k.now());
  }

  // The master's part of a 2.1 frame: FE1 released, dummy 0, six mode bits, then `payload`
  // bits ("" for none) and released from then on.
  static std::string header(std::uint8_t mode_bits, const std::string& payload = "") {
    std::string s = "-0";
    for (int i = 5; i >= 0; --i) s += ((mode_bits >> i) & 1) ? '1' : '0';
    return s + payload;
  }

 private:
  void edge() {
    if (low_) {
      low_ = false;
      m_.clock_out.write(true);
      if (clock_ < clocks_) timer_.start(half_);
      return;
    }
    low_ = true;
    ++clock_;
    m_.clock_out.write(false);
    const char c = clock_ <= drive_.size() ? drive_[clock_ - 1] : '-';
    m_.data_enable.write(c == '0' || c == '1');
    if (c == '0' || c == '1') m_.data_out.write(c == '1');
    timer_.start(half_);
  }

  line::Line::MasterSide m_;
  sim::Time half_;
  unsigned clocks_;
  std::string drive_;
  sim::Timer timer_;
  unsigned clock_ = 0;
  bool low_ = false;
};

// n bits of v, MSB first, as '0'/'1'.
inline std::string bits_msb(std::uint64_t v, unsigned n) {
  std::string s;
  for (unsigned i = n; i-- > 0;) s += ((v >> i) & 1U) ? '1' : '0';
  return s;
}

// n bits of v, LSB first.
inline std::string bits_lsb(std::uint64_t v, unsigned n) {
  std::string s;
  for (unsigned i = 0; i < n; ++i) s += ((v >> i) & 1U) ? '1' : '0';
  return s;
}

// Records DATA at the encoder's pins once per clock period: entry k-1 is slot k-1, the bit the
// encoder put out after RE_(k-1) or the one the master put out at FE_(k-1) for the encoder to
// take at RE_(k-1) (entry 0 is taken at FE1). It is read half-way through the HIGH phase between
// RE_(k-1) and FE_k, where both are stable: the encoder's bit shows one internal delay after
// RE_(k-1), the master's changes at FE_k (its next bit, its driver on or off) may reach the
// pins before FE_k does when its driver switches off or on faster than its CLOCK driver.
class PinSampler {
 public:
  PinSampler(sim::Kernel& k, line::Line& line) : k_(k), pins_(line.pins(line::ObservationPoint::EncoderPins)) {
    pins_.clock.on_change(sim::bind<&PinSampler::on_clock>(this));
    pins_.data.on_change(sim::bind<&PinSampler::on_data>(this));
    data_.emplace_back(sim::Time::min(), pins_.data.read());
  }
  // Bits of slots first..last (inclusive) as a string of '0'/'1'.
  std::string slots(unsigned first, unsigned last) const {
    std::string s;
    for (unsigned k = first; k <= last && k < samples_.size(); ++k) s += samples_[k] ? '1' : '0';
    return s;
  }
  // The same for the frame whose FE1 is the first falling edge at or after t0.
  std::string slots_at(sim::Time t0, unsigned first, unsigned last) const {
    std::size_t base = 0;
    while (base < times_.size() && times_[base] < t0) ++base;
    std::string s;
    for (std::size_t k = base + first; k <= base + last && k < samples_.size(); ++k) s += samples_[k] ? '1' : '0';
    return s;
  }

 private:
  void on_clock(std::uint64_t level) {
    if (level != 0) {
      rise_ = k_.now();
      return;
    }
    const sim::Time at = rise_ ? *rise_ + (k_.now() - *rise_) / 2 : k_.now();
    rise_.reset();
    auto after = std::upper_bound(data_.begin(), data_.end(), at,
                                  [](sim::Time t, const auto& change) { return t < change.first; });
    samples_.push_back(std::prev(after)->second);
    times_.push_back(k_.now());
  }
  void on_data(std::uint64_t level) { data_.emplace_back(k_.now(), level != 0); }
  sim::Kernel& k_;
  line::Line::Pins pins_;
  std::optional<sim::Time> rise_;  // the rising edge before the next falling one
  std::vector<std::pair<sim::Time, bool>> data_;  // every DATA change at the pins
  std::vector<bool> samples_;
  std::vector<sim::Time> times_;
};

}  // namespace endatsim::test_support

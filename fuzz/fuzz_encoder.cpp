// libFuzzer target: the encoder's reaction to arbitrary CLOCK/DATA edge sequences, driven at the
// master's end of the line like tests/test_support.hpp's ScriptedClock, but without any rules.
//
// Input: 6 bytes of encoder and line parameters, then one byte per step: the low two bits say what
// the master side does (0 toggle CLOCK, 1 toggle DATA, 2 toggle the DATA driver enable, 3 nothing),
// the upper six bits how long it waits afterwards (0 .. 47: n x 31.25 ns, 48 .. 63: 4 .. 64 us).
//
// Checked: no crash, exception, UB or leak; the encoder never starts more frames than it saw
// falling clock edges; and once CLOCK has stayed HIGH longer than t_m + t_R, the encoder is idle
// again (spec 2.3: the transfer ends after the recovery time) whatever came before.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "endatsim/line/line.hpp"
#include "endatsim/slave/encoder.hpp"

using namespace endatsim;
using sim::Time;

namespace {

Time step_delay(std::uint8_t code) {
  return code < 48 ? sim::ps(31'250) * code : sim::us(4) * (code - 47);
}

class Driver {
 public:
  Driver(sim::Kernel& k, line::Line& line, const std::uint8_t* steps, std::size_t n)
      : m_(line.master()), steps_(steps), n_(n), timer_(k, sim::bind<&Driver::step>(this)) {
    timer_.start(sim::us(1));
  }
  std::uint64_t falling_edges() const { return falling_; }

 private:
  void step() {
    if (i_ == n_) {
      m_.clock_out.write(true);  // CLOCK HIGH from here on: the encoder must recover
      return;
    }
    const std::uint8_t b = steps_[i_++];
    switch (b & 3U) {
      case 0:
        clock_ = !clock_;
        falling_ += clock_ ? 0 : 1;
        m_.clock_out.write(clock_);
        break;
      case 1:
        data_ = !data_;
        m_.data_out.write(data_);
        break;
      case 2:
        enable_ = !enable_;
        m_.data_enable.write(enable_);
        break;
      default:
        break;
    }
    timer_.start(step_delay(static_cast<std::uint8_t>(b >> 2)));
  }

  line::Line::MasterSide m_;
  const std::uint8_t* steps_;
  std::size_t n_;
  std::size_t i_ = 0;
  sim::Timer timer_;
  bool clock_ = true, data_ = false, enable_ = false;
  std::uint64_t falling_ = 0;
};

[[noreturn]] void fail(const char* what) {
  std::fprintf(stderr, "fuzz_encoder: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  constexpr std::size_t kHeader = 6;
  if (size < kHeader || size > kHeader + 4096) return -1;
  slave::EncoderParams p;
  const std::uint8_t flags = data[0];
  p.version = (flags & 1U) != 0 ? protocol::EndatVersion::V2_1 : protocol::EndatVersion::V2_2;
  p.type1 = (flags & 2U) != 0 ? slave::Type1Handling::NoStartBit : slave::Type1Handling::AbortHigh;
  p.driver_enable_edge = 9 + ((flags >> 2) & 1U);
  if ((flags & 8U) != 0) {
    p.t_m_short = sim::ns(1250) + sim::ns(10) * (data[4] % 250);
    p.short_t_m_selected = (flags & 16U) != 0;
  }
  p.error1 = (flags & 32U) != 0;
  p.continuous_low_bits = 1 + (flags >> 6) + (data[3] & 3U);  // 1 .. 7
  p.position_bits = 1 + data[1] % 48;
  if ((data[2] & 1U) != 0 && p.position_bits > 1) {
    p.kind = slave::EncoderKind::Multiturn;
    p.multiturn_bits = 1 + (data[2] >> 1) % (p.position_bits - 1);
  }
  p.t_cal = sim::ns(100) * (data[3] >> 2);                 // 0 .. 6.3 us
  p.t_m = sim::us(10) + sim::us(1) * (data[4] % 21);       // 10 .. 30 us
  p.t_r = sim::ns(50) * (data[5] & 31U);                   // 0 .. 1.55 us
  p.output_delay = sim::ns(20) * (data[5] >> 5);           // 0 .. 140 ns
  p.motion.start = (std::uint64_t{0x5A5A5A5A5A5A} * (data[1] + 1U)) & ((std::uint64_t{1} << p.position_bits) - 1);
  p.motion.counts_per_s = static_cast<std::int64_t>(data[2]) * 100'000 - 12'800'000;

  line::LineParams lp;
  lp.cable_length_m = static_cast<double>(data[4]);  // 0 .. 255 m
  lp.failsafe_level = (data[2] & 2U) == 0;

  sim::Kernel kernel;
  line::Line line(kernel, lp);
  slave::Encoder encoder(kernel, line, p);
  Driver driver(kernel, line, data + kHeader, size - kHeader);
  kernel.run();  // every step ends, and CLOCK stays HIGH after the last one

  if (encoder.frames().size() > driver.falling_edges()) fail("more frames than falling clock edges");
  if (!encoder.idle()) fail("not idle after CLOCK stayed HIGH beyond t_m + t_R");
  return 0;
}

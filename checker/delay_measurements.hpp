// D297403 2.1.2, the propagation-delay measurement as the wires show it: "This measurement must
// be carried out at least three times, and an arithmetic mean must be found. ... the three
// measured values must not deviate from the calculated mean value by more than 1/8 of the pulse
// duration of the maximum clock pulse frequency f_c."
//
// The master's counter values are its own, but the delays they count are on the wires: each
// measurement frame's t_D at the master's connector (rising edge that carried the start bit to
// the start bit's edge). A master that compensates with measurements the line did not give
// consistently, or with fewer than three, is judged when its first compensated frame comes,
// against T of that frame's clock. A master may discard a round and measure again, or average
// more than three: the measurements pass if the latest three or more of them agree.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "endatsim/sim/time.hpp"

namespace endatsim::checker {

class DelayMeasurements {
 public:
  // What a compensated frame is judged against.
  struct Judgement {
    std::size_t measurements = 0;  // since the last compensated frame
    std::uint64_t first_frame = 0;  // the frame of the earliest of them
    bool enough = false;           // at least three
    // The measurement furthest from the mean of the latest three (or all, if fewer), its
    // deviation rounded to the picosecond, and the limit T/8.
    std::size_t worst = 0;  // 0-based, in the order measured
    std::uint64_t worst_frame = 0;
    sim::Time deviation{0};
    sim::Time limit{0};
    // Deviation against the limit at the resolution (each t_D known to within r; the deviation
    // from the mean to within 2r): true when some three or more latest measurements agree.
    bool consistent = false;
    bool undecided = false;
  };

  // A measurement frame's t_D at the master's connector.
  void measured(std::uint64_t frame, sim::Time t_d);
  // A compensated frame clocked at `period`: a judgement the first time after measurements, and
  // again if the clock is faster than any judged before (its T/8 is tighter). `resolution` is
  // the capture's (0: exact).
  std::optional<Judgement> compensated(sim::Time period, sim::Time resolution);
  bool any() const { return ever_; }
  // Measurements kept: those of the latest run of measurement frames.
  std::size_t kept() const { return run_.size(); }

 private:
  struct Measurement {
    std::uint64_t frame;
    sim::Time t_d;
    bool operator==(const Measurement&) const = default;
  };
  std::vector<Measurement> run_;
  bool closed_ = false;  // a compensated frame has come since the latest measurement
  bool ever_ = false;
  std::optional<sim::Time> judged_period_;

 public:
  bool operator==(const DelayMeasurements&) const = default;
};

}  // namespace endatsim::checker

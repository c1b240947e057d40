// The master's propagation-delay measurement (D297403 2.1.2): during frames of "Encoder send
// position values" at a reduced clock, a counter clocked at f_e runs from a rising clock edge
// until the start bit's rising edge comes back; at least three counts, each within T/8 of their
// mean, give the t_D the master compensates with, and a rejected round is measured again. The
// master's frame engine tells it what happens on the pins; it keeps the counts and the verdicts.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include <boost/random/mersenne_twister.hpp>

#include "endatsim/protocol/timing.hpp"
#include "endatsim/sim/parameter.hpp"
#include "endatsim/sim/time.hpp"

namespace endatsim::master {

using sim::Hertz;
using sim::Time;

// How the f_e counter relates to the clock edges that restart it. A counter on its own
// oscillator runs at an arbitrary phase (a seeded random phase per frame here): its counts
// scatter by one and their mean is unbiased. A counter restarted in phase with the edge
// truncates: every count is floor(t_D x f_e), and the master adds half a count to centre it.
enum class CounterPhase : std::uint8_t { FreeRunning, EdgeAligned };

struct DelayMeasurementParams {
  Hertz f_c = sim::kHz(200);  // 2.1.2: reduced clock 100 .. 200 kHz
  Hertz f_e = 0;              // counter clock; 0 = 8 x the intended f_c (2.1.2: "at least eight times")
  unsigned count = protocol::limit::kMeasurementsMin;  // 2.1.2: at least three measurements, averaged
  unsigned max_rounds = 3;    // further rounds when a value strays more than T/8 from the mean
  CounterPhase counter_phase = CounterPhase::FreeRunning;
};

// The keys of "master.delay_measurement", one row each (sim/parameter.hpp).
std::span<const sim::Parameter<DelayMeasurementParams>> delay_measurement_parameters();

struct DelayMeasurementResult {
  Time start{0};
  bool accepted = false;
  unsigned rounds = 0;
  std::vector<std::int64_t> counts;  // of the accepted (or last) round
  Time counter_period{0};
  Time t_d{0};                       // mean, as used for compensation
  std::string reason;                // why it was rejected
};

class DelayMeasurement {
 public:
  // `f_c` is the clock the master intends to compensate at (T/8 is of its period).
  DelayMeasurement(const DelayMeasurementParams& params, Hertz f_c);

  Time counter_tick() const;
  // A measurement begins with its first round.
  void begin();
  bool active() const { return active_; }

  // The frame engine's news. Every frame stops and clears the counter; a measurement frame on a
  // free-running counter draws its phase from `rng`.
  void frame_started(bool measurement, boost::random::mt19937_64& rng);
  void clock_rose(Time now, unsigned clock);  // the counter starts at each RE from the earliest start bit's
  void data_rose(Time now);                   // "saved with every rising clock pulse edge of the start bit"
  void stop_counter() { running_ = false; }
  // A measurement frame ended with a good answer: its count as a time, none without a count.
  std::optional<Time> take_count();

  // Every frame the master recorded, by its start: a round's first frame is the count-th last.
  void frame_recorded(Time start);
  // Where the round that ends at `now` began: its first frame's start, or `now` when fewer frames
  // than a round were recorded.
  Time round_start(Time now) const;
  // The round is over (its first frame started at `start`): the verdict, kept in results().
  const DelayMeasurementResult& finish_round(Time start);
  // After a rejected round: whether another one may run (then it has begun); otherwise the
  // measurement ends.
  bool next_round();
  // The first keep() verdicts (every one by default: a long run that measures again and again
  // keeps its memory flat), how many there were, and the last.
  const std::vector<DelayMeasurementResult>& results() const { return results_; }
  std::uint64_t results_count() const { return results_count_; }
  const std::optional<DelayMeasurementResult>& last_result() const { return last_; }
  void keep(std::size_t n) { keep_ = n; }

 private:
  DelayMeasurementParams params_;
  Hertz f_c_;
  bool active_ = false;
  unsigned round_ = 0;
  std::vector<std::int64_t> counts_;
  Time counter_start_{0};
  Time counter_phase_{0};
  bool running_ = false;
  std::optional<std::int64_t> captured_;
  std::vector<DelayMeasurementResult> results_;
  std::uint64_t results_count_ = 0;
  std::optional<DelayMeasurementResult> last_;
  std::size_t keep_ = SIZE_MAX;
  std::deque<Time> recent_starts_;  // of the last params_.count frames recorded
};

}  // namespace endatsim::master

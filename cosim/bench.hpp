// cosim/ — a master that lives outside endatsim (an HDL design in Icarus Verilog, GHDL, a
// commercial simulator or a Verilated model) on endatsim's line, encoders, scripted events and
// pin-level checker.
//
// The outside simulator owns time. It moves the bench to each of its instants (advance_to),
// drives the master's pins there (drive), and wakes the bench again at next_event_time() so that
// DATA towards the master changes at the exact instant the line delivers it (on_data_in). The
// bench never runs ahead of the outside simulator, so nothing it computes can be overtaken by a
// pin change the master has yet to make. Like SystemC's split between kernel and models, the
// bench and the master talk through signals only: the checker judges the master from the wires
// (checker/frame_decoder.hpp), the master's own decoded values come back through
// report_position and report_parameter.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "endatsim/checker/frame_decoder.hpp"
#include "endatsim/checker/timing_checker.hpp"
#include "endatsim/scenarios/limits.hpp"
#include "endatsim/scenarios/runner.hpp"
#include "endatsim/scenarios/scenario.hpp"

namespace endatsim::cosim {

using sim::Time;

// The master's outputs (2.1: CLOCK towards the encoder, DATA's driver and its enable).
enum class MasterPin : std::uint8_t { Clock, DataOut, DataEnable };

struct BenchOptions {
  std::optional<std::string> vcd_path;  // both connectors' CLOCK, DATA and driver enables
  std::optional<std::uint64_t> seed;    // overrides the bench's seed
  // Called with each frame the checker's decoder finds at the encoder's connector, as it ends.
  std::function<void(const checker::WireFrame&)> on_frame;
  // Kernel events and records kept (positions, parameters, frames, violations), and a cap on the
  // bench's max_time, as for `endatsim run` (scenarios/limits.hpp); the events list is checked
  // when the bench is built.
  scenarios::Limits limits;
};

// A value the master decoded, as it reported it, against what the wires or the encoder held.
struct Reported {
  Time at{0};
  std::uint64_t value = 0;
  std::optional<std::uint64_t> truth;  // none: nothing to compare with had happened yet
  bool matches() const { return truth == value; }
};

struct BenchResult {
  std::string file, name, description;
  std::uint64_t seed = 0;
  Time simulated{0};
  std::uint64_t events = 0;
  std::uint64_t frames_decoded = 0;  // at the encoder's connector
  std::uint64_t frames_clean = 0;    // with a complete answer and a good CRC
  std::vector<checker::WireFrame> frames;  // the first scenarios::kMaxFramesKept
  std::vector<Reported> positions;   // against the position the encoder latched at FE1
  std::vector<Reported> parameters;  // against the parameter the last decoded answer carried
  std::vector<checker::Violation> violations;
  std::vector<checker::RowConformance> conformance;
  checker::Conclusion conclusion;
  std::vector<scenarios::ExpectationResult> expectations;
  std::vector<std::string> notes;  // what the bridge had to assume (time precision, unknown levels)
  // The frame the simulation's end cut (CLOCK had not been HIGH for t_m since its last pulse), and
  // CLOCK's level and last change at the encoder's connector then: a master that hangs mid-frame.
  std::vector<scenarios::EventNotActed> events_not_acted;  // the bench's events the run ended before
  std::optional<std::uint64_t> frame_cut_by_end;
  bool clock_at_end = true;
  Time clock_last_change{0};
  // Why the run ended before the outside simulator did: a limit reached or a signal; such a
  // result does not pass.
  std::string incomplete;
  int interrupted = 0;  // the signal (SIGINT, SIGTERM) that ended it, or 0
  bool passed() const;
};

class Bench {
 public:
  // `bench`: a scenario loaded as scenarios::ScenarioKind::Bench (no master, no script). Throws
  // scenarios::ScenarioError when the bench asks for more than options.limits grant.
  explicit Bench(const scenarios::Scenario& bench, BenchOptions options = {});
  ~Bench();
  Bench(const Bench&) = delete;
  Bench& operator=(const Bench&) = delete;

  Time now() const;
  // Runs every event up to and including `t`; the outside simulator has reached `t`.
  void advance_to(Time t);
  // The master drives `pin` at the current instant; the change settles before this returns.
  void drive(MasterPin pin, bool level);
  // When the bench must be woken next (an edge on its way along the cable, an encoder timer);
  // none once a limit or a signal stopped it.
  std::optional<Time> next_event_time() const;
  // DATA at the master's receiver output, and a call at each change of it.
  bool data_in() const;
  void on_data_in(std::function<void(Time, bool)> callback);
  // What the master decoded from a position frame or a parameter read, as it ends.
  void report_position(std::uint64_t position);
  void report_parameter(std::uint16_t parameter);
  // A remark for the report (a rounded time, an assumption the bridge made).
  void note(std::string text);
  // A pin of the master at an unknown level (X, Z, U …): noted, and the run fails "pins at known
  // levels" (a master whose outputs go unknown is broken even when the line survives it).
  void unknown_level(std::string text);
  // True once the outside simulator should stop: the bench's max_time has passed, a limit was
  // reached or SIGINT/SIGTERM asked to stop (scenarios/interrupt.hpp). From then on the bench
  // stands still: advance_to and drive do nothing.
  bool should_stop();
  // The bench's max_time, or the limit's when that is earlier.
  Time max_time() const { return max_time_; }

  // Ends the run: evaluates what is open and judges the expectations. Call once.
  BenchResult finish();

 private:
  struct Parts;
  void on_data_in_change(std::uint64_t level);
  void on_master_clock(std::uint64_t level);
  void on_master_data(std::uint64_t level);
  void on_encoder_clock(std::uint64_t level);
  void on_encoder_data(std::uint64_t level);
  void drain_frames();
  void check_limits();
  void end_early(const std::string& why, int signal = 0);
  std::uint64_t records() const;
  // The max_time limit, earlier than the bench's own max_time, ended the run at `end`.
  bool cut_by_time_limit(Time end) const;
  void judge(BenchResult& r) const;

  const scenarios::Scenario& bench_;
  BenchOptions options_;
  std::unique_ptr<Parts> parts_;
  std::function<void(Time, bool)> data_in_callback_;
  std::vector<Reported> positions_;
  std::vector<Reported> parameters_;
  std::vector<std::string> notes_;
  std::uint64_t unknown_levels_ = 0;
  std::uint64_t frames_decoded_ = 0;
  std::uint64_t frames_clean_ = 0;
  std::vector<checker::WireFrame> frames_;
  std::optional<std::uint16_t> last_parameter_on_wires_;
  bool finished_ = false;
  scenarios::Limits limits_;
  Time max_time_;
  std::string incomplete_;
  int interrupted_ = 0;
};

}  // namespace endatsim::cosim

// The passive protocol analyzer's timing monitors (TimingChecker): they see only committed changes
// of the line's signals at the master's and the encoder's pins (and, where a master declares
// them, its sampling instants), decode every frame from the wires (frame_decoder.hpp) and judge
// each row of the timing table (protocol/timing.hpp; D297403 2.3.2, 2.1.2, 2.3.3, appendix A2)
// against the spec's envelope or the declared encoder. The checks are spread over
// timing_checker.cpp (frames, the clock's frequency, the rows between frames),
// clock_phase_checks.cpp (t_HI, t_LO, the on-off ratio) and data_line_checks.cpp (t_z, t_OE,
// t_cal, t_ST, t_D, the number of clock pulses); what each row found is a Violation, what it
// measured a RowConformance.
#pragma once

#include <algorithm>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "endatsim/line/line.hpp"
#include "endatsim/checker/activated_settings.hpp"
#include "endatsim/checker/clock_fit.hpp"
#include "endatsim/checker/declarations.hpp"
#include "endatsim/checker/delay_measurements.hpp"
#include "endatsim/checker/decision.hpp"
#include "endatsim/checker/row_margins.hpp"
#include "endatsim/checker/frame_decoder.hpp"
#include "endatsim/checker/power_on.hpp"
#include "endatsim/protocol/timing.hpp"
#include "endatsim/sim/tape.hpp"

namespace endatsim::checker {

using line::ObservationPoint;
using sim::Time;

// Undecided: the measured value is within the capture's resolution of the limit (decision.hpp).
enum class Severity : std::uint8_t { Error, Warning, Undecided };
std::string_view to_string(Severity s);

// Names of the checks, as used in scenarios' expectations and in reports: one per row of the
// timing table (protocol/timing.hpp).
namespace check {
using namespace protocol::check;
// Every check name, in the timing table's order, for loaders and reports.
std::span<const std::string_view> all();
}  // namespace check

// Which verdict a finding counts against. D297403 2.3.2 gives some of the encoder's times as a
// range that each encoder fills in (t_m 10 .. 30 us, t_cal up to 1 ms, "t_ST maximum: see encoder
// specifications"): a master must suit every compliant encoder (the spec envelope), or at least
// the encoder it is used with (its declaration). A fixed limit of the spec counts against both.
enum class Verdict : std::uint8_t { Both, SpecEnvelope, ThisEncoder };
std::string_view to_string(Verdict v);

// What a check found; a Violation adds where in the frame it happened.
struct Finding {
  std::string check;
  std::string spec;  // section / table row
  ObservationPoint where = ObservationPoint::EncoderPins;
  Time time{0};
  std::optional<std::uint64_t> frame;
  std::optional<unsigned> clock;  // bit slot (RE index) inside the frame
  std::string measured;
  std::string limit;
  Severity severity = Severity::Error;
  std::string message;
  Verdict verdict = Verdict::Both;
  bool operator==(const Finding&) const = default;
};

struct Violation : Finding {
  // Where in the frame: "start-bit polling", "start bit", "position", "CRC", "first LOW phase"...
  std::string field;
  bool operator==(const Violation&) const = default;
};

// The same finding `shift` later, of a frame `index_shift` higher (the frame-level fast path).
inline Violation moved(Violation v, Time shift, std::uint64_t index_shift) {
  v.time += shift;
  if (v.frame) *v.frame += index_shift;
  return v;
}

// The two verdicts of a run: does the master conform to the spec envelope, and to the declared
// encoder? (Warnings count against neither.) A verdict without an error finding but with a
// finding undecided at the capture's resolution is undecided, never conforming.
struct Conclusion {
  bool spec_envelope = true;  // no error finding counts against it
  bool this_encoder = true;
  bool spec_envelope_undecided = false;  // an undecided finding counts against it
  bool this_encoder_undecided = false;
  // Conforms: no error finding and no undecided one.
  bool conforms_to_spec_envelope() const { return spec_envelope && !spec_envelope_undecided; }
  bool conforms_to_this_encoder() const { return this_encoder && !this_encoder_undecided; }
  // Counts one finding against the verdicts it belongs to.
  void count(Severity severity, Verdict verdict);
};
Conclusion conclude(std::span<const Violation> violations);

// How a row fared in a run: judged (how often, how many violations), or why it was not.
struct RowConformance {
  std::string check;
  enum class Status : std::uint8_t { Judged, NotApplicable, NotObservable } status = Status::NotApplicable;
  std::uint64_t judged = 0;      // occasions the row was evaluated (frames, words, samples, accesses)
  std::uint64_t violations = 0;  // of error severity
  std::uint64_t warnings = 0;
  std::uint64_t undecided = 0;   // within the capture's resolution of the limit
  std::string reason;            // for a row that was not judged
  std::string relaxed_by;        // a named option that loosened the row's limit in this run
  std::vector<WorstCase> worst;  // the measured value nearest to (or furthest past) each limit
};
std::string_view to_string(RowConformance::Status s);

struct CheckerParams {
  // The master's sampling flip-flop: DATA must be stable this long before and after the instant.
  Time sample_setup = sim::ps(1);
  Time sample_hold = sim::ps(1);
  // f_c limits are applied with this allowance (oscillator tolerance); 0 checks them exactly.
  std::int64_t f_c_tolerance_ppm = 1000;
  // t_z and t_OE "max T = 1/f_c min" (2.3.2 note 6): read as one period of the frame's own clock
  // (default; docs/model.md §7, met by an encoder that turns DATA around in 60 ns up to 16 MHz,
  // as the model's default encoder does), or literally as the period at the lowest f_c, 10 us
  // (false). On the wires alone the release after FE1 waits for the frame's f_c; a frame that
  // never shows two rising edges is judged against 10 us.
  bool t_z_per_frame_period = true;
  // t_ST (2.3.2 note 8): "the 2 us relate to a cable length of 100 m and can be reduced with a
  // shorter cable". By default the note's own values are required (2 us up to 8 MHz, 1 us at
  // 16 MHz) whatever the cable; with this option they are scaled by the cable's share of the t_D
  // bound, (0.2 + 0.01 L) / 1.2, and every t_ST finding says so.
  bool t_st_reduced_for_cable = false;
  // A capture that holds no driver enables: the encoder is taken to drive DATA from the
  // turnaround on (2.3), and the rows that need the enables (t_z, t_OE, floating data,
  // contention) are not observable.
  bool driver_enables_observable = true;
  // The master's DATA driver enable is known too (a simulation, or a capture of both enables):
  // without it a collision of the two drivers is not observable.
  bool master_enable_observable = true;
  // Edge times are known to within this (a logic analyzer's sample period); 0: exact event
  // times. A limit closer than this to the measured value is reported as undecided.
  Time resolution{0};
  // Findings kept per check (all are counted): a long capture that breaks a row in every frame
  // keeps its memory bounded.
  std::size_t max_findings_per_check = SIZE_MAX;
  // The cable between master and encoder, when the line the checker watches is not it (a
  // capture replayed without delays): t_D's bound, t_ST and f_c's 100 m follow it.
  std::optional<double> cable_length_m;
  // The round trip (t_D) shows only where the master's DATA receiver is: not at the encoder's
  // connector.
  bool round_trip_observable = true;
  // A capture shows one connector: the line it is replayed on has two ends without delay
  // between them, and only this one's findings are the capture's (a contention, once).
  std::optional<line::ObservationPoint> recorded_at;
  // At the master's connector: the round trip the encoder's bits are read with was given (the
  // user's --t-d), not estimated from the cable. Without it, or a delay measurement in the capture
  // that shows it, a compensated frame's start bit cannot be placed on the edge that carried it.
  bool round_trip_given = true;
};

// The keys of a scenario's "checker" object, one row each (sim/parameter.hpp); the other fields
// are set by the command that judges (a capture's resolution, its connector).
std::span<const sim::Parameter<CheckerParams>> checker_parameters();

// The rows that a named option loosens under `params`, each with the option and what it accepts
// (RowConformance::relaxed_by): every report of a run or capture names them.
struct Relaxation {
  std::string check;
  std::string by;
};
std::vector<Relaxation> relaxations(const CheckerParams& params);

// Timing monitors. With delay compensation, the pulse-width minimum is the on-off ratio row's
// (HIGH and LOW each at least 50 % - 10 % of the period); without it, the 0.2 us of t_HI and t_LO
// apply (2.3.2). The alternative reading (0.2 us in both cases) would forbid every f_c above
// 2.5 MHz, which the same table allows.
class TimingChecker final {
 public:
  // `master` matters only if the master declares its frames (the calls below); a master that
  // only drives pins is judged from the wires alone.
  TimingChecker(sim::Kernel& kernel, line::Line& line, const EncoderDeclaration& encoder,
                const MasterDeclaration& master = {}, const CheckerParams& params = {});
  TimingChecker(const TimingChecker&) = delete;
  TimingChecker& operator=(const TimingChecker&) = delete;

  // A cooperating master declares its frames: at FE1 (at its logic, before the edge reaches the
  // encoder), at each sampling instant of bit slot `clock`, and at the frame's end.
  void on_frame_start(const DeclaredFrame& frame);
  void on_sample(const DeclaredFrame& frame, unsigned clock);
  void on_frame_end(const DeclaredFrame& frame);

  // The transmission path changed (cable, connector): t_D must be measured again (2.1.2).
  void on_line_change() { t_d_stale_ = true; }
  // The encoder's supply came back after an interruption: t_D must be measured again (2.1.2),
  // word 3 as written is active (3.4.4), and the power-on conditions (2.3.3) apply again unless
  // the run does not model switching on (`judge_power_on` false).
  void on_switched_on(bool judge_power_on = true);

  // A capture's window opens at `start`: a frame its end cuts is not judged on the rows that need
  // the frame's end (clock_count, start-bit polling). Unless the capture shows the line at rest
  // at its start (`at_rest`: a simulation from time 0), it may open inside a frame, and its first
  // frame begins only once CLOCK has been HIGH for t_m (FrameDecoder::begin_capture). Call before
  // the capture's first CLOCK level; a live run never does.
  void begin_capture(Time start, bool at_rest);
  // A capture's times became less certain (a VCD time that fell between two picoseconds): limits
  // from now on are undecided within `r`. Never lowers the resolution.
  void raise_resolution(Time r) { params_.resolution = std::max(params_.resolution, r); }
  Time resolution() const { return params_.resolution; }
  // The capture's window closes at `end`, at or after its last change (call before finish()).
  void end_capture(Time end) { capture_end_ = end; }
  // Clock edges of a capture skipped before its first frame, and the frame its end cut.
  std::uint64_t edges_before_first_frame() const { return decoder_.edges_before_first_frame(); }
  // At the master's connector, the round trip the capture's last delay measurement showed.
  std::optional<Time> measured_round_trip() const { return measured_round_trip_; }
  std::optional<std::uint64_t> frame_cut_by_end() const { return frame_cut_by_end_; }

  // The run stopped at `end` before the master was done (a limit, or the scenario's max_time): a
  // frame still going on then was cut, and the number of its clock pulses is not judged, as when a
  // capture ends inside a frame. Call before finish().
  void end_run_early(Time end) { run_cut_at_ = end; }
  // Evaluates what is still open (last frame, running contention). Call once after the run.
  void finish();

  // Findings as they are made, for outputs written while the run goes on. The listener is called
  // from inside the checker for every finding at the moment it is reported, whether or not it is
  // kept in violations() (CheckerParams::max_findings_per_check bounds only those), in the order
  // reported: not in time order, since many rows are judged after their frame (below). One
  // listener; setting another replaces it, an empty one removes it. It must not call back into
  // the checker other than through its const members.
  using FindingListener = std::function<void(const Violation&)>;
  void set_finding_listener(FindingListener listener) { listener_ = std::move(listener); }

  // The watermark of attributed findings: no finding reported from now on names a frame
  // (Finding::frame) below this index, so an output may close every frame below it. Findings
  // often come after their frame: a frame is judged at the encoder pins when the next FE1
  // arrives there, a start bit's t_D when it reaches the master logic, a compensated frame's
  // delay measurements when it is judged, a power-on wake-up request cycle when the next request
  // comes (or at finish()), a contention when it ends (with a master's declarations; judged from
  // the wires, once no frame found later can have begun before it); a contention that begins
  // between frames counts against the frame before. Never decreases; UINT64_MAX after finish().
  // Frame indices are the master's declarations' (strictly increasing, each declared at its FE1),
  // or the wire decoder's: in a live run judged from the wires the mark stays at 0 until a frame
  // carries a mode command, since a master that declares its frames may still do so after its
  // power-on pulse, which the wires show as a frame (on_frame_start).
  std::uint64_t settled_frames() const;

  // What the checker holds for findings still to come, the memory of a long run: each count is
  // bounded by a frame's worth (its clock edges, words, start bits and contentions), a run of
  // delay-measurement frames, or the findings kept (max_findings_per_check per row), however
  // many frames the run has. Only a CLOCK that the encoder pins do not show as the master sent
  // it stretches "a frame": while the pin is stuck, declared frames wait for their FE1 there, and
  // after an extra falling edge (a glitch) no declared FE1 is found there again, so the frame
  // at the encoder pins lasts to the end of the run.
  struct Backlog {
    std::size_t frames_not_at_encoder = 0;  // declared frames whose FE1 is on its way to the encoder
    std::size_t frame_starts = 0;           // FE1s that contentions may still be attributed to
    std::size_t contentions = 0;            // contentions begun and not yet reported
    std::size_t start_bits_in_flight = 0;
    std::size_t master_rising_edges = 0;    // of the current frame, at the master logic
    std::size_t master_driven_changes = 0;  // of DATA driven at the master pins, this frame
    std::size_t encoder_edges = 0;          // rising and falling, of the frame at the encoder pins
    std::size_t delay_measurements = 0;     // the current run of measurement frames
    std::size_t findings_kept = 0;          // violations()
  };
  Backlog backlog() const;
  // True when no master declared its frames: they were found on the wires at the encoder pins
  // (frame_decoder.hpp), and only the rows that need nothing but wires were judged.
  bool judged_from_wires() const { return wires_only_; }

  // The frame-level fast path (docs/performance.md). What the checker holds between two frames,
  // but for what it has counted, noted and kept: taken at the start and the end of a recorded
  // frame, and put back, moved in time, after the frame is played again (restore). While the
  // kernel records, each finding is noted on the tape (take_recorded_findings); replay() reports
  // it again. A frame's worst cases need nothing: the same values noted again change none.
  struct Snapshot;
  // Between frames of a run whose master declares them, with nothing pending that belongs to no
  // frame (a contention, the power-on conditions) and the whole run still to be judged.
  bool replayable() const;
  std::shared_ptr<const Snapshot> snapshot() const;
  // `later` is `earlier` moved by `shift` and `index_shift` (frame indices).
  static bool same_moved(const Snapshot& earlier, const Snapshot& later, Time shift, std::uint64_t index_shift);
  // What a frame counted (clock edges, rows judged), the same in both.
  static bool same_counts(const Snapshot& start0, const Snapshot& end0, const Snapshot& start1, const Snapshot& end1);
  // After a frame recorded between `start` and `end` was played `shift` later: the state at `end`,
  // moved, and the counts of the frame added.
  void restore(const Snapshot& start, const Snapshot& end, Time shift, std::uint64_t index_shift);
  std::vector<Violation> take_recorded_findings() { return std::exchange(recorded_, {}); }
  void replay(const sim::TapeItem& item, const std::vector<Violation>& findings, Time shift, std::uint64_t index_shift);
  const std::vector<Violation>& violations() const { return violations_; }
  // The verdicts over every finding, kept or not.
  const Conclusion& conclusion() const { return conclusion_; }
  // Findings counted but not kept (max_findings_per_check).
  std::uint64_t findings_not_kept() const { return not_kept_; }
  // Every row of the timing table, in its order, with how it fared (call after finish()).
  std::vector<RowConformance> conformance() const;

 private:
  struct FrameHeader {
    std::uint64_t index = 0;
    bool measurement = false;
    bool compensated = false;
    protocol::EndatVersion command_type = protocol::EndatVersion::V2_1;
    unsigned payload_bits = 0;  // master bits after the mode bits (2.1 parameter frames)
    unsigned answer_bits = 0;   // the encoder's answer, start bit to the last CRC
    bool supplement = false;    // a 2.2 command supplement follows the answer
    bool continuous = false;    // "Encoder send position values": clocks beyond the word are a continuous clock (2.3.1)
    sim::Hertz f_c = 0;
    Time t_d_used{0};
    unsigned supplement_last_clock = 0;  // found on the wires: the rising edge that took its last bit
    bool operator==(const FrameHeader&) const = default;
  };
  // The clock edges of one frame at the encoder pins; the buffers are reused frame after frame.
  struct PinFrame {
    FrameHeader header;
    Time fe1{0};
    std::vector<Time> rising;
    std::vector<Time> falling;
    bool operator==(const PinFrame&) const = default;
  };

  void on_encoder_clock(std::uint64_t level);
  // Encoder-side rows of 2.3.2, at the encoder pins (data_line_checks.cpp).
  void on_encoder_driver(std::uint64_t enabled);
  // The encoder's release after FE1 (t_z): measured, at, on clock.
  struct Release {
    Time t_z;
    Time at;
    unsigned clock;
    bool operator==(const Release&) const = default;
  };
  // The bound of t_z and t_OE: one period of the frame's clock, or 10 us read literally; none
  // while the frame's f_c is not known yet.
  std::optional<Time> turnaround_bound() const;
  void judge_release(const Release& r, Time bound);
  void settle_pending_release();
  void on_encoder_data(std::uint64_t level);
  unsigned carrying_clock() const;
  void first_start_bit();
  void start_bit_from_decoder(unsigned clock);
  void check_calculation_time_maximum();
  void next_word_start_bit(unsigned clock);
  void note_start_bit_for_t_d();
  void on_master_data(std::uint64_t level);
  void start_data_line_checks();
  void note_encoder_low();
  void on_master_driven(std::uint64_t driven);
  void check_start_delay(const PinFrame& f);
  struct StartBitInFlight;
  void check_data_delay(const StartBitInFlight& s, Time t_d);
  void check_delay_tolerance(const StartBitInFlight& s, Time t_d);
  void check_memory_access_time();
  void check_calculation_time_minimum();
  void power_on_request(std::uint64_t index, Time start);
  void report_power_on(const std::optional<PowerOnSequence::Judgement>& j);
  void begin_wire_frame(Time now);
  void refresh_wire_header();
  Time clock_path() const;
  double cable_length_m() const { return params_.cable_length_m.value_or(line_.params().cable_length_m); }
  void check_clock_count(const PinFrame& f);
  // Which rising edge carried a compensated frame's start bit is not known (round_trip_given).
  bool start_edge_unknown(bool compensated) const;
  Time start_edge_uncertainty() const;
  unsigned start_edge_uncertainty_clocks() const;
  bool start_bit_timing_decided(bool parameter_frame) const;
  void report_start_edge_unknown(std::size_t row_index, std::string_view row, const std::string& spec, unsigned clock,
                                 std::string measured, Time at, std::string_view field);
  void check_start_bit_timing();
  void check_start_bit_polling(const PinFrame& f);
  struct PollingLimit {
    std::string_view check, spec, symbol;
    std::optional<Time> declared;  // this encoder's longest time, if declared
    Time envelope;                 // the spec's maximum
  };
  void judge_polling(const PinFrame& f, Time from, const PollingLimit& limit);
  void check_time_between_cycles(const PinFrame& next, Time last_rise);
  // What t_ac needs of a frame, from the master's declaration or from the wires.
  struct AccessEvidence {
    std::uint64_t index = 0;
    Time start{0};
    Time end{0};
    protocol::ModeCommand command = protocol::ModeCommand::EncoderSendPositionValues;
    std::optional<std::uint32_t> supplement;
    bool ok = false;
    std::optional<bool> busy;  // additional data 1's Busy bit, if sent
    sim::Hertz f_c = 0;
  };
  void check_busy_time(const AccessEvidence& frame);
  void check_access_while_busy(const AccessEvidence& frame);
  std::string field_of(const DeclaredFrame& frame, unsigned clock) const;
  unsigned bits_of(const DeclaredFrame& frame) const;
  void check_encoder_sample(unsigned clock);
  void check_master_sample(const DeclaredFrame& frame, unsigned clock);
  void on_master_clock(std::uint64_t level);
  void evaluate(const PinFrame& f);
  void check_pulse_widths(const PinFrame& f);
  void check_on_off_ratio(const PinFrame& f);
  void check_frequency(const PinFrame& f);
  void check_frequency_for_cable(const PinFrame& f, const FittedFrequency& fit);
  void check_frequency_for_encoder(const PinFrame& f, const FittedFrequency& fit);
  void check_recovery(const PinFrame& next);
  void check_measurement_procedure(const DeclaredFrame& frame);
  bool measures_delay(const FrameHeader& h) const;
  void check_measurement_spread(const PinFrame& f);
  // Counts the finding for its row and the verdicts, tells the listener, and keeps it unless its
  // check already has CheckerParams::max_findings_per_check.
  void report(Finding f, std::string_view field = {});
  void report(Violation v, std::optional<std::uint64_t> contention);
  void find_latest_contention_kept();
  // Line contentions (2.3, collision of the data drivers), told by the line as they begin and end.
  void on_contention(const line::Contention& c);
  void contention_frame_started(Time start, std::uint64_t index);
  void settle_contentions(bool finishing = false);
  bool contentions_reported() const {
    return params_.driver_enables_observable && params_.master_enable_observable;
  }
  void drop_given_up_start_bits();
  // Reports `f` if `d` fails, as undecided if it is undecided at the resolution; true if reported.
  bool report_unless_passed(Decision d, Finding f, std::string_view field = {});
  // The same, and notes the measured value against the limit for the row's worst case.
  bool report_unless_passed(const Judgement& j, Finding f, std::string_view field = {});
  // The worst case of the row named `check` (a time, frequency or count against its limit).
  void note(std::string_view check, const Judgement& j, LimitOf of = LimitOf::Spec) {
    margins_.note(protocol::check::row_of(check), j, of);
  }
  void note(std::string_view check, std::int64_t measured, std::int64_t limit, Bound bound, Unit unit,
            LimitOf of = LimitOf::Spec) {
    margins_.note(protocol::check::row_of(check), measured, limit, bound, unit, of);
  }
  // A row was evaluated once (whatever its verdict), for the conformance table.
  // Rows that are evaluated per sample count once per frame (word).
  void judge(std::size_t row) { ++judged_[row]; }

  sim::Kernel& kernel_;
  line::Line& line_;
  // The pins' signals, looked up once: they are read on every clock edge.
  line::Line::Pins encoder_pins_;
  line::Line::Pins master_pins_;
  EncoderDeclaration encoder_;
  MasterDeclaration master_;
  CheckerParams params_;

  std::uint64_t master_falling_edges_ = 0;
  std::uint64_t encoder_falling_edges_ = 0;
  std::deque<std::pair<std::uint64_t, FrameHeader>> pending_;  // frames whose FE1 has not reached the encoder
  PinFrame current_;
  bool in_frame_ = false;
  struct FrameEnd {
    Time last_rise;
    protocol::EndatVersion command_type;
    std::uint64_t index;
    bool operator==(const FrameEnd&) const = default;
  };
  std::optional<FrameEnd> previous_end_;
  std::optional<std::uint64_t> error_handling_frame_;  // the last master frame that ended in an error handling
  std::optional<Time> busy_since_;  // a 2.2 memory access began with this frame's supplement (t_ac)
  bool busy_reported_ = false;
  std::optional<std::uint64_t> awaiting_not_busy_;
  bool awaiting_known_ = false;  // a 2.2 access has been seen: later accesses are judged  // the 2.2 memory access no Busy = 0 has followed yet
  // Changes of "DATA driven" at the master pins during the current frame, to judge samples: the
  // latest one at or before the master's sampling instants can see, and any later.
  std::deque<std::pair<Time, bool>> master_driven_;
  bool floating_reported_ = false;
  std::vector<Time> master_rising_;  // rising edges of the current frame at the master logic
  bool sampling_reported_ = false;
  bool last_frame_was_measurement_ = false;
  bool t_d_stale_ = false;
  bool measured_ = false;
  bool unmeasured_reported_ = false;
  std::uint64_t sampled_frame_ = UINT64_MAX;
  // FE1 at the master logic and the frame's index, in the order noted: the latest one at or
  // before now and any later, the frames a contention that begins from now on can belong to.
  std::deque<std::pair<Time, std::uint64_t>> frame_starts_;
  // A contention from its beginning until it is reported, with the frame that had begun (FE1
  // at the master logic) when it began, as far as the frames noted so far show.
  struct PendingContention {
    line::Contention contention;
    std::optional<std::uint64_t> frame;
  };
  std::deque<PendingContention> contentions_;  // in the order they began
  // The frames a finding may still name: the master's declarations (the latest one, and
  // whether it is still running at the master), a frame whose findings are being reported after
  // its state was let go (power-on), and whether a frame found on the wires carried a mode
  // command.
  std::optional<std::uint64_t> last_declared_;
  bool declared_running_ = false;
  std::optional<std::uint64_t> held_frame_;
  bool wire_request_seen_ = false;
  std::optional<std::uint64_t> frozen_mark_;  // settled_frames() while finish() reports
  bool finished_ = false;
  // The encoder pins counted more falling edges than the next declared frame's FE1 needs (a clock
  // glitch at the encoder): no declared frame will begin there any more.
  bool fe1_lost_ = false;
  FindingListener listener_;
  // Per kept violation, how finish() orders it among findings of the same time: the others in
  // the order reported, then contentions in the order they began (as when all contentions were
  // reported by finish()).
  std::vector<std::optional<std::uint64_t>> contention_of_;
  std::optional<std::size_t> latest_contention_kept_;  // the kept contention that began last
  // Per frame, at the encoder pins: driver released (t_z), driver on again (t_OE), the first
  // word's start bit seen on rising edge `start_clock_` (t_cal, clock count), the current word's
  // on `word_start_clock_` (with a continuous clock words count from 0); DATA last went LOW on
  // rising edge `low_clock_`.
  bool released_ = false;
  bool driving_ = false;
  bool driven_low_ = false;
  bool low_at_last_rise_ = false;  // DATA LOW at the frame's latest rising edge (start-bit polling)
  Time last_data_rise_{0};  // DATA's latest rising edge at the pins watched
  // The encoder's release after FE1, measured before the wires showed the frame's f_c (its second
  // rising edge): judged once they do (t_z per frame period, 2.3.2 note 6).
  std::optional<Release> pending_release_;
  std::optional<std::uint64_t> master_found_start_bit_;  // the last declared frame whose master read one
  unsigned start_clock_ = 0;
  unsigned word_start_clock_ = 0;
  unsigned word_ = 0;
  unsigned low_clock_ = 0;
  // A start bit seen at the encoder pins, on its way to the master logic, where t_D ends (2.3.2).
  struct StartBitInFlight {
    Time due;         // at the master logic: the encoder pins' time + cable + master receiver
    Time carried_at;  // the rising clock edge that carried it, at the master logic
    std::uint64_t frame;
    unsigned clock;
    bool compensated;
    Time t_d_used;
    Time period;
    bool measurement;  // the first word of a propagation-delay measurement frame (2.1.2)
    bool operator==(const StartBitInFlight&) const = default;
  };
  std::deque<StartBitInFlight> start_bits_in_flight_;
  // A capture at the master's connector: the round trip its last delay measurement showed (slow
  // enough to leave no doubt which edge carried the start bit). Later frames' bits are found one
  // such round trip after their edges, not one assumed (--t-d), which at a fast clock could put
  // a start bit on the wrong edge and measure t_D against that one.
  std::optional<Time> measured_round_trip_;
  // Frames found on the wires when no master declares its own (decided at the first FE).
  FrameDecoder decoder_;
  ActivatedSettings settings_;  // word 3 as the wires have set and activated it
  DelayMeasurements delay_measurements_;  // t_D of each measurement frame, at the master's pins
  std::optional<std::uint64_t> first_frame_;  // the first frame the checker saw
  bool unmeasured_on_wires_reported_ = false;
  bool measurements_may_precede_ = false;  // compensated frames, no measurement, no switch-on seen
  std::optional<WireFrame> last_wire_;  // the frame the decoder finished last
  bool recovery_checked_ = true;
  bool mode_decided_ = false;
  bool wires_only_ = false;
  std::vector<Violation> violations_;
  std::vector<std::uint64_t> judged_;  // per row of protocol::timing_rows()
  struct Tally {
    std::uint64_t errors = 0, warnings = 0, undecided = 0;
  };
  std::vector<Tally> tally_;  // findings per row, kept or not
  RowMargins margins_;        // the worst case of each row, passed or not
  PowerOnSequence power_on_;
  bool measurement_seen_ = false;  // a delay-measurement frame (2.1.2) on the wires
  Conclusion conclusion_;
  std::uint64_t not_kept_ = 0;
  std::uint64_t sample_judged_frame_ = UINT64_MAX;
  bool capture_ = false;  // begin_capture() was called
  std::optional<std::uint64_t> frame_cut_by_end_;
  Time cut_at_{0};  // where the run or the capture ended inside frame_cut_by_end_
  std::optional<Time> run_cut_at_;  // end_run_early()
  Time capture_end_{0};
  std::vector<Violation> recorded_;  // findings while the kernel records
  bool contention_recorded_ = false;  // a contention was reported while recording: not replayable
};

}  // namespace endatsim::checker

// master/ — the subsequent electronics (D297403 2.1 .. 2.3). Master is the frame engine and the
// operation scheduler: clock generation (f_c, duty cycle, t_ST, seeded jitter; CLOCK idles
// HIGH), mode commands on falling edges, start-bit polling, CRC checks, recovery waits, and the
// expansion of a script's operations into frames. It only talks through the line's master-side
// signals, and hands what the frames bring to its parts:
//   delay_measurement.hpp  the propagation-delay measurement and its verdict (2.1.2)
//   parameter_book.hpp     the encoder's memory as read (2.4 .. 2.6)
//   safety.hpp             the safety functions' checks of every frame (SafetyMonitor)
//   diagnostics.hpp        the diagnosis for a service engineer (DiagnosisMonitor, A3)
//   frame_result.hpp       what a frame gave; operation.hpp what the master is asked to do
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <vector>

#include <boost/random/mersenne_twister.hpp>

#include "endatsim/sim/parameter.hpp"
#include "endatsim/line/line.hpp"
#include "endatsim/master/delay_measurement.hpp"
#include "endatsim/master/diagnostics.hpp"
#include "endatsim/master/frame_result.hpp"
#include "endatsim/master/operation.hpp"
#include "endatsim/master/parameter_book.hpp"
#include "endatsim/master/safety.hpp"
#include "endatsim/protocol/protocol.hpp"

namespace endatsim::master {

using protocol::ModeCommand;
using sim::Hertz;
using sim::Time;

// How the master finds the start bit while it polls (2.3: "observe the data line to detect the
// start bit"). Fail-safe receivers read HIGH on the undriven line during the turnaround
// (docs/model.md §1, §11), so a careful master first waits for the encoder's LOW (HPMicro's SEI
// sample: "wait 0, then wait 1"); a simple one takes the first HIGH sample after the mode bits.
enum class StartBitDetection : std::uint8_t { WaitLowThenHigh, FirstHigh };

// How the master checks CRCs (masters in the field got each of these wrong, docs/model.md §12).
// The defaults are the spec's (appendix A4).
struct CrcCheck {
  protocol::CrcConfig generator;     // preset and final inversion
  bool endat22_rule_for_21 = false;  // 2.1 frames checked with F2 included, as 2.2 frames are
  // A table-driven CRC whose loop ends one bit early at this position width (0 = none):
  // a library reported wrong only for 31 position clocks (docs/model.md §12).
  unsigned table_fault_width = 0;
  // A comparator stuck at "equal": every CRC passes (what the CRC self-test is for).
  bool accept_any = false;
};

// What a careful master does when things go wrong. Each reaction can be switched off
// to reproduce a careless master.
struct CarefulMaster {
  unsigned retries = 0;            // a failed frame of a script operation is repeated up to this often
  bool verify_echo = true;         // 2.1 parameter frames: an echo other than what was sent fails
  // 2.1.2: "a new measurement is necessary after power interruption or a change of the
  // transmission path" (with delay compensation).
  bool remeasure_after_line_change = true;
  bool remeasure_after_power_interruption = true;
  unsigned remeasure_after_crc_errors = 3;  // consecutive failed frames; 0 = never
  // After a power interruption the encoder has forgotten its additional data (2.4.2.2): select
  // them again before reading on.
  bool reselect_after_power_interruption = true;
};

struct MasterParams {
  Hertz f_c = sim::MHz(1);
  unsigned high_permille = 500;  // duty cycle: HIGH share of the period
  Time t_st{0};                  // first LOW phase stretched to t_ST (2.3.2 note 8); 0 = not stretched
  Time jitter{0};                // peak edge jitter, uniform in [-jitter, +jitter], seeded
  std::uint64_t seed = 1;
  bool delay_compensation = false;
  // A delay value set by hand instead of measured (compensation uses it from the first frame).
  std::optional<Time> fixed_t_d;
  DelayMeasurementParams measurement;
  unsigned position_bits = 25;   // word 13 as the master has it configured
  // docs/model.md §5: one more clock pulse after the last bit (its falling edge samples the
  // last bit) — or none, sampling the last bit half a period after the last rising edge.
  bool extra_clock_after_last_bit = true;
  Time t_m_wait = sim::us(30);   // CLOCK held HIGH after a frame: at least t_m of the encoder
  Time t_r_wait = sim::ns(500);  // then t_R before the next FE1 (2.3.2)
  Time error_wait = sim::us(30); // A2: "after an error handling, the maximum t_m of 30 us must be waited"
  Time reset_wait = sim::ms(50); // German brochure's start-up routine: "50 ms warten" after the reset
  // 2.3.2 t_b > 1 ms before a 2.1 memory or parameter frame (read as end of the previous frame
  // to FE1; see the checker's t_b row).
  Time t_b_wait = sim::us(1100);
  // 2.3.3 (the figure's labels in the German brochure, TI's reading; docs/model.md §8): after
  // switching on, CLOCK stays at a valid level for t1 >= 800 ms and HIGH for t2 = 80 .. 120 ms,
  // then at least one LOW pulse > 125 ns, then HIGH for t3 = 380 .. 420 ms before the first request.
  struct PowerOnSequence {
    Time t1_t2 = sim::ms(900);
    Time pulse = sim::us(1);
    Time t3 = sim::ms(400);
  } power_on;
  // The start-up routine reads word 13 and from then on clocks that many position bits.
  bool adopt_word13 = true;
  // ... and runs at this clock: before t_D is known only a slow clock is safe on a long cable
  // (TI's firmware runs the routine at 200 kHz).
  Hertz startup_f_c = sim::kHz(200);
  Time start_bit_timeout = sim::ms(1);  // t_cal max (2.3.2); polling gives up after this
  // 2.1 parameter frames: polling after the 24 bits gives up after t_ac max (12 ms, 2.3.2) + 1 ms.
  Time memory_access_timeout = sim::ms(13);
  // docs/model.md §4 (TI's choice, "can optimize"): LOW bits the master drives before the start
  // bit of a 2.2 command supplement, from the first falling edge after it has checked the answer.
  unsigned supplement_lead_bits = 7;
  // Of those, the master drives only the last ones: before them DATA is left undriven, so that
  // the encoder's release can travel the cable back first (a turnaround like t_ST's).
  unsigned supplement_driven_lead_bits = 2;
  unsigned type1_detect_samples = 8;    // HIGH samples after the turnaround, no LOW: type I (docs/model.md §10)
  StartBitDetection start_bit_detection = StartBitDetection::WaitLowThenHigh;
  CrcCheck crc;
  CarefulMaster careful;
  SafetyParams safety;
  DiagnosticsParams diagnostics;

  static constexpr Hertz kMinFc = sim::kHz(100);
  static constexpr Hertz kMaxFc = sim::MHz(16);
  // Throws std::invalid_argument naming the parameter and its limit.
  void validate() const;
};

// The scalar keys of "master" and of its objects "power_on" and "careful", one row each
// (sim/parameter.hpp); validate() checks their ranges, the loader reads them, the schema and
// docs/parameters.md come from them.
std::span<const sim::Parameter<MasterParams>> master_parameters();
std::span<const sim::Parameter<MasterParams::PowerOnSequence>> power_on_parameters();
std::span<const sim::Parameter<CarefulMaster>> careful_parameters();

// What monitors and reports can observe of the master's intentions.
class MasterObserver {
 public:
  virtual ~MasterObserver() = default;
  virtual void on_frame_start(const FrameResult& frame) = 0;
  // The master samples DATA for bit slot `clock` (the bit the encoder sent after RE_clock).
  virtual void on_sample(const FrameResult& frame, unsigned clock, bool value, bool in_data) = 0;
  virtual void on_frame_end(const FrameResult& frame) = 0;
  // A result recorded: each frame as it ends (after on_frame_end), and each further word of a
  // continuous clock (2.3.1) as its CRC arrives, which ends no frame. For outputs written while
  // the run goes.
  virtual void on_result(const FrameResult&) {}
};

// What VerifyChecksum found (3.5.26).
struct ChecksumCheck {
  bool complete = false;  // every word was read
  std::uint16_t stored = 0;    // word 47
  std::uint16_t computed = 0;  // word 4 + ... + word 46, overflow ignored
  bool ok() const { return complete && stored == computed; }
};

// What the start-up routine found (docs/model.md §8).
struct StartupInfo {
  bool completed = false;  // every frame of the routine answered without error
  std::optional<std::uint16_t> errors;    // operating status word 0, before clearing (3.4.1)
  std::optional<std::uint16_t> warnings;  // word 1 (3.4.2)
  std::optional<std::uint16_t> word13;    // clock pulses for the position value (3.5.6)
  std::optional<std::uint16_t> word37;    // EnDat command set (3.5.22)
  unsigned failed_frames = 0;
};

class Master {
 public:
  Master(sim::Kernel& kernel, line::Line& line, const MasterParams& params);
  Master(const Master&) = delete;
  Master& operator=(const Master&) = delete;

  void add_observer(MasterObserver* o) { observers_.push_back(o); }
  void enqueue(Operation op) {
    op.script_index = enqueued_++;
    operations_.push_back(op);
  }
  void start();  // begins the queued operations at the current time
  bool finished() const { return finished_; }

  const MasterParams& params() const { return params_; }
  // The first frames recorded (every one unless keep_frames() said fewer): a long run streams
  // its results through MasterObserver::on_result instead of keeping them.
  const std::vector<FrameResult>& frames() const { return frames_; }
  void keep_frames(std::size_t n) { kept_frames_ = n; }
  std::uint64_t frame_count() const { return frame_count_; }  // every frame and word recorded
  const std::vector<DelayMeasurementResult>& measurements() const { return delay_.results(); }
  std::optional<Time> t_d() const { return t_d_; }
  std::uint64_t cycle_overruns() const { return cycle_overruns_; }
  std::uint64_t busy_timeouts() const { return busy_timeouts_; }
  // await_not_busy operations given up at once because a poll frame came back (without error)
  // carrying no additional data 1, where the busy bit travels (D297403 2.5.1, 2.6.1): polling
  // on could never see it reset.
  std::uint64_t busy_unreadable() const { return busy_unreadable_; }
  const StartupInfo& startup() const { return startup_; }
  const std::optional<ChecksumCheck>& checksum() const { return checksum_; }
  std::uint64_t retries() const { return retries_done_; }
  std::uint64_t remeasurements() const { return remeasurements_; }
  const SafetyReport& safety() const { return safety_.report(); }
  const DiagnosisReport& diagnosis() const { return diagnosis_.report(); }
  // A parameter word as last read or written with 2.1 frames (area by MRS code, 2.4.1).
  std::optional<std::uint16_t> parameter(std::uint8_t mrs, std::uint8_t address) const { return book_.parameter(mrs, address); }
  // What the installation tells the master (the runner's events): another cable, and the
  // encoder's supply back after an interruption (CarefulMaster says what the master does then).
  void line_changed();
  void encoder_power_interrupted();
  unsigned position_bits() const { return position_bits_; }
  // What the master has selected with 2.4.2.2 MRS codes: it expects this many additional data.
  unsigned expected_additional_data() const { return (selected_[0] ? 1U : 0U) + (selected_[1] ? 1U : 0U); }

  sim::Signal& sample_strobe() { return sample_strobe_; }  // toggles at each sampling instant
  sim::Signal& frame_active() { return frame_active_; }

 private:
  enum class Rx : std::uint8_t { Off, Polling, Receiving, Done };

  // The operations the master expands from one script operation (a routine, a memory read, a
  // setup): they share its script index and run before what is queued.
  struct Sequence {
    std::size_t script_index = 0;
    std::vector<Operation> ops;
    Operation& frame(ModeCommand c, std::uint8_t address = 0, std::uint16_t parameter = 0,
                     Operation::Purpose purpose = Operation::Purpose::None, unsigned word = 0);
    Operation& add(Operation::Kind k);
  };
  Sequence sequence() const { return {current_->script_index, {}}; }
  void run_first(const Sequence& s);
  void next_operation();
  void expand(void (Master::*expansion)());
  void operation_frame_done();
  void start_frame(std::uint64_t);
  void clock_edge();
  void falling_edge();
  void rising_edge();
  void sample(std::uint64_t tag);
  void sample_now(unsigned clock);
  void word_received(FrameOutcome outcome);
  void end_reception(FrameOutcome outcome, bool answer_complete = false);
  void maybe_complete_frame();
  void on_data_in(std::uint64_t level);
  void power_on_pulse(std::uint64_t phase);
  void expand_startup_routine();
  void note_startup(const FrameResult& f);
  void expand_checksum_check();
  void note_checksum_word(const FrameResult& f);
  bool retry_frame();
  void note_failures();
  void interrupt_for_measurement();
  // Safety functions (safety.cpp).
  void expand_safety_startup();
  void expand_endat22_read();
  void run_crc_self_test();
  bool crc_passes(std::uint8_t received, std::uint8_t expected) const;
  void note_safety(FrameResult& f);
  void collect_words(const FrameResult& f);
  void finish_checksums(bool endat22);
  bool startup_position_read(const FrameResult& f);
  // Additional data 1 in turn (diagnostics.cpp).
  std::vector<protocol::Information> additional_data_1_schedule() const;
  void roll_additional_data_1();
  // Diagnosis (diagnostics.cpp).
  void expand_diagnosis_setup();
  void activate_diagnosis();
  void push_status_reads(const Operation& base);
  Time time_between_cycles_left() const;
  std::uint8_t expected_crc_pos(unsigned bits, bool error1, bool error2, bool v22, std::uint64_t position) const;
  FrameOutcome check_echo(FrameOutcome outcome) const;
  void incomplete(std::uint64_t tag);
  void decode_answer();
  void drive_supplement_bit();
  void release_supplement();
  void note_selection();
  unsigned answer_width() const;
  void finish_measurement_round();
  Time jittered(Time nominal);

  sim::Kernel& kernel_;
  line::Line::MasterSide pins_;
  MasterParams params_;
  std::vector<MasterObserver*> observers_;
  boost::random::mt19937_64 rng_;
  sim::Signal sample_strobe_;
  sim::Signal frame_active_;
  sim::Timer edge_timer_;
  sim::Timer operation_timer_;

  // Operations.
  std::deque<Operation> operations_;
  std::optional<Operation> current_;
  std::size_t enqueued_ = 0;
  unsigned frames_left_ = 0;
  Time next_due_{0};
  Time ready_at_{0};
  bool finished_ = false;
  std::uint64_t cycle_overruns_ = 0;
  std::uint64_t busy_timeouts_ = 0;
  std::uint64_t busy_unreadable_ = 0;
  StartupInfo startup_;
  std::optional<ChecksumCheck> checksum_;
  std::vector<std::uint16_t> checksum_words_;
  unsigned checksum_read_ = 0;
  bool reselect_due_ = false;
  unsigned retries_left_ = 0;
  std::uint64_t retries_done_ = 0;
  unsigned failures_in_a_row_ = 0;
  bool remeasure_due_ = false;
  std::uint64_t remeasurements_ = 0;
  std::uint8_t selection_mrs_[2] = {0, 0};  // the MRS codes behind selected_
  SafetyMonitor safety_{params_.safety};
  // Diagnosis.
  DiagnosisMonitor diagnosis_{params_.diagnostics};
  ParameterBook book_;               // the encoder's memory as read (2.4 .. 2.6)
  std::size_t ai1_slot_ = 0;         // where additional data 1 is in its schedule
  unsigned startup_agreeing_ = 0;
  std::uint64_t startup_previous_ = 0;
  Time startup_previous_at_{0};
  unsigned position_bits_ = 0;  // as configured, or as word 13 said
  bool selected_[2] = {false, false};

  // The frame on the wire.
  FrameResult frame_;
  bool frame_running_ = false;
  Hertz f_ = 0;
  Time high_{0}, low_{0};
  Time nominal_{0};
  bool clock_low_ = false;
  unsigned clock_ = 0;
  unsigned last_clock_ = 0;  // 0 while unknown (start bit not found yet)
  bool clocking_done_ = false;
  std::uint8_t mode_bits_ = 0;
  const protocol::ModeCommandInfo* command_ = nullptr;
  std::uint32_t payload_ = 0;
  std::uint32_t supplement_word_ = 0;  // 8 + 16 bits of this frame's payload or supplement
  unsigned supplement_start_ = 0;  // FE of the first lead bit; 0 = not started
  bool supplement_due_ = false;
  protocol::Layout layout_;
  Rx rx_ = Rx::Off;
  bool seen_low_ = false;
  bool require_low_ = true;
  unsigned words_left_ = 0;
  Time poll_start_{0};
  unsigned high_samples_ = 0;
  std::vector<std::uint8_t> rx_bits_;
  std::uint64_t epoch_ = 0;

  DelayMeasurement delay_;   // 2.1.2
  std::optional<Time> t_d_;  // what compensation uses: measured, or params.fixed_t_d

  void record(const FrameResult& f);
  std::vector<FrameResult> frames_;
  std::size_t kept_frames_ = SIZE_MAX;
  std::uint64_t frame_count_ = 0;
  std::deque<Time> recent_starts_;  // of the last measurement.count frames (a measurement round's start)
};

}  // namespace endatsim::master

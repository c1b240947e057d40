// The master's frame engine (D297403 2.3): one frame on the wire at a time. It generates CLOCK
// (f_c, duty cycle, t_ST, seeded jitter; CLOCK idles HIGH), sends the mode command and any
// 2.1 payload or 2.2 command supplement on falling edges, samples DATA (at the falling edge, or
// t_D after it with delay compensation), polls for the start bit, receives the answer and checks
// its CRCs. What to send it is told by a FrameRequest; what came back goes to its FrameClient,
// the operation scheduler (Master), which decides what the next frame is.
#pragma once

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "endatsim/line/line.hpp"
#include "endatsim/master/clock_timing.hpp"
#include "endatsim/master/delay_measurement.hpp"
#include "endatsim/master/frame_result.hpp"
#include "endatsim/master/master_params.hpp"
#include "endatsim/master/start_bit_hunt.hpp"
#include "endatsim/protocol/protocol.hpp"
#include "endatsim/sim/tape.hpp"

namespace endatsim::master {

// The CRC the master expects for a position or test-value answer, as its CrcCheck computes it
// (the spec's by default, appendix A4), and whether a received CRC passes against it.
std::uint8_t expected_crc_pos(const CrcCheck& check, unsigned bits, bool error1, bool error2, bool v22,
                              std::uint64_t position);
bool crc_passes(const CrcCheck& check, std::uint8_t received, std::uint8_t expected);

// One frame as the scheduler asks for it.
struct FrameRequest {
  std::uint64_t index = 0;    // FrameResult::index of its first word
  std::size_t operation = 0;  // Operation::script_index
  bool measurement = false;   // a frame of a propagation-delay measurement (2.1.2)
  ModeCommand command = ModeCommand::EncoderSendPositionValues;
  std::uint8_t mode_bits = 0;   // as sent (a fault may send others than the command's)
  std::uint32_t payload = 0;    // address << 16 | parameter: the 2.1 payload or the 2.2 supplement
  Hertz f_c = 0;
  std::optional<Time> t_d;      // compensate with this delay (2.3); none: sample at the falling edge
  unsigned position_bits = 0;
  unsigned continuous_words = 0;  // further words without a new mode command (2.3.1)
  int clock_adjust = 0;           // a fault: this many clock pulses more (or fewer) than the answer needs
  bool operator==(const FrameRequest&) const = default;
};

// What the frame engine asks of and tells the scheduler while a frame runs.
class FrameClient {
 public:
  virtual ~FrameClient() = default;
  // How many additional data the master has selected and so expects after a 2.2 position (2.4.2.2).
  virtual unsigned expected_additional_data() const = 0;
  // An answer came in whole and clean, before any command supplement follows it.
  virtual void answer_accepted(const FrameResult& frame) = 0;
  // A word of a continuous clock is in (2.3.1); the frame clocks on.
  virtual void word_done(const FrameResult& frame) = 0;
  // The frame is over: CLOCK is back HIGH and nothing more is received.
  virtual void frame_done(FrameResult& frame) = 0;
};

class FrameEngine {
 public:
  FrameEngine(sim::Kernel& kernel, line::Line::MasterSide pins, const MasterParams& params, DelayMeasurement& delay,
              FrameClient& client, const std::vector<MasterObserver*>& observers);
  FrameEngine(const FrameEngine&) = delete;
  FrameEngine& operator=(const FrameEngine&) = delete;

  void start(const FrameRequest& request);  // FE1 now
  const FrameResult& frame() const { return frame_; }  // the frame on the wire, or the last one
  // CLOCK outside a frame (the power-on pulse of 2.3.3).
  void drive_clock(bool level) { pins_.clock_out.write(level); }

  sim::Signal& sample_strobe() { return sample_strobe_; }  // toggles at each sampling instant
  sim::Signal& frame_active() { return frame_active_; }

  // The frame-level fast path (docs/performance.md). While the kernel records (Kernel::tape()),
  // the engine notes on the tape each time it tells its observers or its client of the frame,
  // with the frame as it was then (take_recorded_frames()); replay() tells them again.
  enum class Note : std::uint32_t { Start, Sample, Accepted, WordDone, Done };
  std::vector<FrameResult> take_recorded_frames() { return std::exchange(recorded_, {}); }
  // Plays one noted item of a frame recorded `shift` earlier, whose index was `index_shift` lower.
  void replay(const sim::TapeItem& item, const std::vector<FrameResult>& frames, Time shift, std::uint64_t index_shift);
  // Some observer but `skip` wants the sampling instants (MasterObserver::wants_samples).
  bool samples_wanted(const MasterObserver* skip) const;

 private:
  void note(Note n, std::uint64_t data = 0);
  enum class Rx : std::uint8_t { Off, Polling, Receiving, Done };

  void clock_edge();
  void next_edge(Time delay);
  void edge_due(std::uint64_t epoch);
  void falling_edge();
  void rising_edge();
  void sample(std::uint64_t tag);
  void sample_now(unsigned clock);
  void begin_answer(unsigned clock);
  void word_received(FrameOutcome outcome);
  void end_reception(FrameOutcome outcome, bool answer_complete = false);
  void maybe_complete_frame();
  void on_data_in(std::uint64_t level);
  void incomplete(std::uint64_t tag);
  void decode_answer();
  void decode_additional_data(bool& ok);
  FrameOutcome check_echo(FrameOutcome outcome) const;
  void drive_supplement_bit();
  void release_supplement();
  unsigned answer_width() const;

  sim::Kernel& kernel_;
  line::Line::MasterSide pins_;
  const MasterParams& params_;
  DelayMeasurement& delay_;
  FrameClient& client_;
  const std::vector<MasterObserver*>& observers_;
  ClockTiming timing_;  // when each edge is due; its generator also draws the delay counter's phase
  sim::Signal sample_strobe_;
  sim::Signal frame_active_;
  // The clock's next edge is a kernel entry that carries this; an abort moves it on, so that the
  // entry queued before finds it changed and does nothing.
  std::uint64_t edge_epoch_ = 0;

  FrameResult frame_;
  bool frame_running_ = false;
  int clock_adjust_ = 0;
  bool clock_low_ = false;
  unsigned clock_ = 0;
  unsigned last_clock_ = 0;  // 0 while unknown (start bit not found yet)
  bool clocking_done_ = false;
  const protocol::ModeCommandInfo* command_ = nullptr;
  std::uint32_t payload_ = 0;          // 8 + 16 bits of a 2.1 payload (0 for a measurement)
  std::uint32_t supplement_word_ = 0;  // 8 + 16 bits of a 2.2 command supplement
  unsigned supplement_start_ = 0;      // FE of the first lead bit; 0 = not started
  bool supplement_due_ = false;
  protocol::Layout layout_;
  Rx rx_ = Rx::Off;
  StartBitHunt hunt_;
  unsigned words_left_ = 0;
  Time poll_start_{0};
  std::vector<std::uint8_t> rx_bits_;
  std::uint64_t epoch_ = 0;
  std::vector<FrameResult> recorded_;  // the frame as each note saw it, while the kernel records
  const FrameResult* replayed_ = nullptr;  // which recorded state frame_ holds while replaying
};

}  // namespace endatsim::master

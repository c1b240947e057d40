// master/ — the subsequent electronics (D297403 2.1 .. 2.3). Master is the operation scheduler:
// it expands a script's operations into frames (routines, memory reads, setups), paces them
// (cycles, recovery waits, t_b, retries) and hands each frame to its parts:
//   frame_engine.hpp       one frame on the wire: clock, mode command, sampling, CRC checks
//   pacing.hpp             when the next frame is due: the operation's cycle, the encoder's waits
//   busy_polling.hpp       await_not_busy: polls until Busy is reset, and how the waits ended
//   careful_policy.hpp     retries and new measurements when frames fail (a careful master)
//   additional_data_selection.hpp  additional data 1 and 2 as the encoder accepted them (2.4.2.2)
//   delay_measurement.hpp  the propagation-delay measurement and its verdict (2.1.2)
//   parameter_book.hpp     the encoder's memory as read (2.4 .. 2.6)
//   startup.hpp            the start-up routine and the checksum check (2.1 reads, 3.5.26), the
//                          frames that read the EnDat 2.2 area (2.5.1)
//   master_params.hpp      what the master is configured with
//   frame_result.hpp       what a frame gave; operation.hpp what the master is asked to do, and
//                          the OperationQueue of what is still to run
// The functions on top of it (master_function.hpp, functions.hpp: the safety functions, the
// diagnosis, additional data 1 in turn) plan the operations they own and see every frame.
// It only talks through the line's master-side signals, all of which the frame engine drives.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "endatsim/line/line.hpp"
#include "endatsim/master/additional_data_selection.hpp"
#include "endatsim/master/busy_polling.hpp"
#include "endatsim/master/careful_policy.hpp"
#include "endatsim/master/delay_measurement.hpp"
#include "endatsim/master/frame_engine.hpp"
#include "endatsim/master/frame_result.hpp"
#include "endatsim/master/master_function.hpp"
#include "endatsim/master/master_params.hpp"
#include "endatsim/master/operation.hpp"
#include "endatsim/master/pacing.hpp"
#include "endatsim/master/parameter_book.hpp"
#include "endatsim/master/startup.hpp"
#include "endatsim/protocol/protocol.hpp"
#include "endatsim/sim/record_log.hpp"

namespace endatsim::master {

using protocol::ModeCommand;
using sim::Hertz;
using sim::Time;
// The frame-level fast path (docs/performance.md): asked before each frame goes on the wire
// whether it plays the frame from a recording instead (true: it has, and told the master of it
// as the frame engine would have).
class FrameShortcut {
 public:
  virtual ~FrameShortcut() = default;
  virtual bool replayed(const FrameRequest& request) = 0;
};

class Master : private FrameClient {
 public:
  Master(sim::Kernel& kernel, line::Line& line, const MasterParams& params);
  Master(const Master&) = delete;
  Master& operator=(const Master&) = delete;

  void add_observer(MasterObserver* o) { observers_.push_back(o); }
  // A function on top of the scheduler; functions see each frame in the order they were added.
  void add_function(MasterFunction& f) { functions_.push_back(&f); }
  void enqueue(Operation op) { operations_.enqueue(std::move(op)); }
  void start();  // begins the queued operations at the current time
  bool finished() const { return finished_; }

  const MasterParams& params() const { return params_; }
  // The first frames recorded (every one unless keep_frames() said fewer): a long run streams
  // its results through MasterObserver::on_result instead of keeping them.
  const std::vector<FrameResult>& frames() const { return frames_.records(); }
  void keep_frames(std::size_t n) {
    frames_.keep(n);
    delay_.keep(n);
  }
  std::uint64_t frame_count() const { return frames_.count(); }  // every frame and word recorded
  // The first measurements kept (keep_frames() bounds them too), how many ran, and the last.
  const std::vector<DelayMeasurementResult>& measurements() const { return delay_.results(); }
  std::uint64_t measurements_count() const { return delay_.results_count(); }
  const std::optional<DelayMeasurementResult>& last_measurement() const { return delay_.last_result(); }
  std::optional<Time> t_d() const { return t_d_; }
  std::uint64_t cycle_overruns() const { return pacing_.cycle_overruns(); }
  std::uint64_t busy_timeouts() const { return busy_polling_.timeouts(); }
  // await_not_busy operations given up at once because a poll frame came back (without error)
  // carrying no additional data 1, where the busy bit travels (D297403 2.5.1, 2.6.1): polling
  // on could never see it reset.
  std::uint64_t busy_unreadable() const { return busy_polling_.unreadable(); }
  const StartupInfo& startup() const { return routine_.info(); }
  const std::optional<ChecksumCheck>& checksum() const { return checksum_.result(); }
  std::uint64_t retries() const { return careful_.retries(); }
  std::uint64_t remeasurements() const { return careful_.remeasurements(); }
  // A parameter word as last read or written with 2.1 frames (area by MRS code, 2.4.1).
  std::optional<std::uint16_t> parameter(std::uint8_t mrs, std::uint8_t address) const { return book_.parameter(mrs, address); }
  // What the installation tells the master (the runner's events): another cable, and the
  // encoder's supply back after an interruption (CarefulMaster says what the master does then).
  void line_changed();
  void encoder_power_interrupted();
  unsigned position_bits() const { return position_bits_; }
  // What the master has selected with 2.4.2.2 MRS codes: it expects this many additional data.
  unsigned expected_additional_data() const override { return selection_.count(); }

  void set_shortcut(FrameShortcut* shortcut) { shortcut_ = shortcut; }
  FrameEngine& engine() { return engine_; }
  // Frames the current operation has still to run, this one included; a measurement round runs.
  unsigned frames_left() const { return frames_left_; }
  bool measuring() const { return delay_.active(); }

  sim::Signal& sample_strobe() { return engine_.sample_strobe(); }  // toggles at each sampling instant
  sim::Signal& frame_active() { return engine_.frame_active(); }

 private:
  Sequence sequence() const { return {current_->script_index, {}}; }
  FunctionContext context() const;
  void next_operation();
  void expand(Sequence s);
  void offer_to_functions(Time begin);
  void start_frames(Time begin);
  void operation_frame_done(const FrameResult& f);
  void start_frame(std::uint64_t);
  FrameRequest frame_request();
  // FrameClient: what the frame engine tells of the frame on the wire.
  void answer_accepted(const FrameResult& f) override;
  void word_done(const FrameResult& f) override;
  void frame_done(FrameResult& f) override;
  void power_on_pulse(std::uint64_t phase);
  Sequence endat22_read_plan();
  void note_endat22_word(const FrameResult& f);
  bool retry_frame(const FrameResult& f);
  void interrupt_for_measurement();
  void roll_additional_data_1(FrameRequest& request);
  bool status_read_due() const;
  void push_status_reads(const Operation& base);
  Time time_between_cycles_left() const;
  void finish_measurement_round();
  void record(const FrameResult& f);

  sim::Kernel& kernel_;
  MasterParams params_;
  std::vector<MasterObserver*> observers_;
  std::vector<MasterFunction*> functions_;
  DelayMeasurement delay_;   // 2.1.2
  std::optional<Time> t_d_;  // what compensation uses: measured, or params.fixed_t_d
  FrameEngine engine_;
  sim::Timer operation_timer_;

  // Operations.
  OperationQueue operations_;
  std::optional<Operation> current_;
  unsigned frames_left_ = 0;
  Pacing pacing_;
  bool finished_ = false;
  BusyPolling busy_polling_;  // await_not_busy (2.5.1, 2.6.1)
  StartupRoutine routine_;
  ChecksumVerification checksum_;
  CarefulPolicy careful_;
  AdditionalDataSelection selection_;  // as the encoder accepted it (2.4.2.2)
  ParameterBook book_;               // the encoder's memory as read (2.4 .. 2.6)
  unsigned position_bits_ = 0;  // as configured, or as word 13 said
  FrameShortcut* shortcut_ = nullptr;

  // What has been recorded.
  sim::RecordLog<FrameResult> frames_{sim::RecordLog<FrameResult>::Keep::First};
};

}  // namespace endatsim::master

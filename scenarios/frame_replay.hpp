// The frame-level fast path (docs/performance.md): a frame that would be the same as one run
// before it, moved in time, is played from that one's recording instead of being run edge by
// edge. The master's scheduler, the VCD writer and the outputs run their own code on what is
// played (they are shown every change and every declaration at its instant); the frame engine,
// the encoder and the line, whose frame is the same, are not run. The checker is shown the frame
// too, or, when its state and findings repeated with the frame, put where the recorded frame
// left it, moved in time, with its findings told again. A recording is played only once the two
// recordings before it of its kind (the sampling strobe's level at FE1 alternates frame by frame)
// agreed, and only when nothing else can happen in the frame's time. Every listener of a signal
// that is not a monitor belongs to the models a recording stands for (the line's delays and
// resolvers, the frame engine, the encoder); a scenario event that counts clock edges keeps
// frames from being played. docs/performance.md says how and what it gives.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "endatsim/checker/timing_checker.hpp"
#include "endatsim/line/line.hpp"
#include "endatsim/master/master.hpp"
#include "endatsim/scenarios/declarations.hpp"
#include "endatsim/scenarios/events.hpp"
#include "endatsim/sim/tape.hpp"
#include "endatsim/sim/vcd.hpp"
#include "endatsim/slave/encoder.hpp"

namespace endatsim::scenarios {

// How a run is carried out: `event` runs every edge as an event (to fall back on and to compare
// with); `auto` (the default) plays the frames that repeat from recordings and runs every other
// frame at the event level; `fast` does the same and says how many frames it played.
enum class Engine : std::uint8_t { Event, Auto, Fast };
std::string_view to_string(Engine e);
std::optional<Engine> engine_from(std::string_view name);

// The parts of a recording (FrameReplay): at namespace scope, so that their default member
// initializers are usable inside FrameReplay (std::optional of a nested struct is not, in Clang).
namespace frame_replay {

// A recording as it is played: what the monitors are shown and the models' notes, in order;
// the signals no monitor observes only as they stand at the end. With a VCD writer the only action
// at the end of a time step, what it writes is prepared too (sim::VcdWriter::Stretch): each run of
// time steps with nothing else played between them is one VcdSteps item (`index` the first step,
// `value` how many), and the signals only it observes are played as they stand at the end.
struct Playback {
  enum class Kind : std::uint8_t { Commit, Monitor, StepEnd, VcdSteps, Model };
  struct Item {
    Time at;  // from the frame's start
    Kind kind;
    std::uint32_t index;
    const void* who;
    std::uint64_t value;
  };
  struct Final {
    sim::Signal* signal;
    bool value;
    Time last_change;  // from the frame's start
    std::uint64_t changes;
  };
  std::vector<Item> items;
  std::vector<Final> finals;
  Time end{0};  // the last change on the tape, from the frame's start
  std::optional<sim::VcdWriter::Stretch> vcd;
};
struct Recording {
  master::FrameRequest request;
  Time start{0};
  Time gap{0};  // since the frame before began
  bool strobe = false;  // the sampling strobe's level at FE1: recordings of one level are played for frames of that level
  sim::Tape tape;
  std::vector<master::FrameResult> frames;
  std::vector<slave::EncoderFrame> encoder_frames;
  std::uint64_t contentions = 0;  // the line's count when the recording began
  std::uint64_t ignored_edges = 0;  // the encoder's count of clock edges it did not take, then
  std::uint64_t event_actions = 0;  // the scenario events' count of actions, then
  bool vcd_quiet = false;  // the VCD writer had nothing waiting for the end of the time step, then
  bool confirmed = false;         // the recording before it of its kind was the same, moved in time
  std::uint64_t epoch = 0;        // when it was made (FrameReplay::epoch_)
  std::optional<Playback> playback;  // once confirmed, made when it is first played
  // The checker's part: its state at the start and at the end, its findings. When the recording
  // before it of its kind agrees on these too, the checker is put in place instead of being
  // shown the frame.
  std::shared_ptr<const checker::TimingChecker::Snapshot> checker_start, checker_end;
  std::vector<checker::Violation> findings;
  bool checker_confirmed = false;
  unsigned checker_attempts = 0;  // recordings of its kind in a row whose checker part did not repeat
};

}  // namespace frame_replay

class FrameReplay final : public master::FrameShortcut {
 public:
  // `room` says whether the run's limits leave room for `events` more kernel events and `records`
  // more records (frames and findings kept): the run ends at a limit between two events, which a
  // played frame must not pass.
  struct Room {
    virtual ~Room() = default;
    virtual bool for_frame(std::uint64_t events, std::uint64_t records) const = 0;
  };
  // `declarations` tells the checker of the master's frames (the checker is fed or put in place
  // through it); `vcd` is the run's VCD writer, if any.
  FrameReplay(sim::Kernel& kernel, line::Line& line, master::Master& master, slave::Encoder& encoder,
              const EventDriver& events, const Room& room, MasterDeclarations& declarations, sim::VcdWriter* vcd);
  FrameReplay(const FrameReplay&) = delete;
  FrameReplay& operator=(const FrameReplay&) = delete;
  ~FrameReplay() override;

  bool replayed(const master::FrameRequest& request) override;
  std::uint64_t frames_replayed() const { return replayed_; }

 private:
  using Playback = frame_replay::Playback;
  using Recording = frame_replay::Recording;
  bool same_checker_part(const Recording& earlier, const Recording& later, Time shift, std::uint64_t index_shift) const;
  Playback compile(const Recording& r) const;
  bool prepares_vcd(const Recording& r) const;
  bool steady(const master::FrameRequest& request) const;
  // Ends the recording begun at the frame before; true if it confirmed the one before it.
  bool close_recording();
  bool may_play(const Recording& r, const master::FrameRequest& request) const;
  void play(const Recording& r, const master::FrameRequest& request);

  sim::Kernel& kernel_;
  line::Line& line_;
  master::Master& master_;
  slave::Encoder& encoder_;
  const EventDriver& events_;
  const Room& room_;
  MasterDeclarations& declarations_;
  checker::TimingChecker& checker_;
  sim::VcdWriter* vcd_;
  std::optional<Recording> recording_;
  std::array<std::optional<Recording>, 2> last_;  // by the sampling strobe's level at FE1
  std::uint64_t replayed_ = 0;
  // Counts the stretches of frames recorded alike or played; a recording plays only in its own.
  std::uint64_t epoch_ = 0;
  bool played_ = false;  // the frame before was played
  std::optional<Time> last_start_;  // when the frame before began
  std::uint64_t events_after_play_ = 0;  // the kernel's count at the next frame if nothing else ran
};

}  // namespace endatsim::scenarios

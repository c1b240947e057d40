// What a run keeps of its frames while it goes, so that its memory does not grow with its length:
// counts for the summary and the expectations, the few examples a report shows, and the
// comparison of each good read with what the encoder latched. Every frame, with the findings the
// checker attributes to it, goes to the outputs (RunSink) in order as soon as no check can add a
// finding to it any more (checker::TimingChecker::settled_frames).
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "endatsim/checker/timing_checker.hpp"
#include "endatsim/master/master.hpp"
#include "endatsim/scenarios/scenario.hpp"
#include "endatsim/slave/encoder.hpp"

namespace endatsim::scenarios {

struct ScenarioResult;

// An output written while the run goes (a log, the results file).
class RunSink {
 public:
  virtual ~RunSink() = default;
  // Before the first frame: the result's name, file, seed and widths are set, and its
  // conformance table says which rows an option relaxed (nothing is counted yet).
  virtual void begin(const ScenarioResult& header) = 0;
  // Each frame (and each further word of a continuous clock) in order, with the checker's
  // findings for it in the order of their time.
  virtual void frame(const ScenarioResult& header, const master::FrameResult& frame,
                     std::span<const checker::Violation> findings) = 0;
  // The run's result, judged; its lists hold what RunOptions::kept kept.
  virtual void end(const ScenarioResult& result) = 0;
};

// Counts over every frame of a run, kept or not.
struct FrameTally {
  static constexpr std::size_t kFailedExamples = 5;
  std::uint64_t results = 0;  // frames and continuous-clock words, measurement frames included
  std::uint64_t measurement_frames = 0;
  std::array<std::uint64_t, master::kFrameOutcomes.size()> outcomes{};  // of the other frames
  std::vector<master::FrameResult> failed;            // the first kFailedExamples not read Ok
  std::optional<master::FrameResult> first_position;  // the first position read without error
  std::uint64_t outcome(master::FrameOutcome o) const { return outcomes[static_cast<std::size_t>(o)]; }
  std::uint64_t frames() const { return results - measurement_frames; }  // without measurement frames
  void add(const master::FrameResult& f);
};

// Where each master frame began at the encoder: FE1 reaches the encoder logic after the master's
// clock driver, the cable and the encoder's receiver; the cable is the scenario's or one that
// an event put in.
std::vector<sim::Time> clock_paths(const Scenario& s);

// The encoder frame that began with the master frame `f`, among `frames` (oldest first, a
// recent window is enough): of several cables that would fit, the frame that came first.
const slave::EncoderFrame* encoder_frame_of(const master::FrameResult& f, std::span<const sim::Time> paths,
                                            std::span<const slave::EncoderFrame> frames);

// Good position reads against the positions the encoder latched (positions_match_encoder),
// one frame at a time: the first difference ends the comparison.
class PositionComparator {
 public:
  // `ef`: the encoder frame that began with `f` (encoder_frame_of), or none.
  void add(const master::FrameResult& f, const slave::EncoderFrame* ef);
  bool match() const { return detail_.empty() && compared_ != 0; }
  std::string detail() const;

 private:
  std::uint64_t compared_ = 0;
  std::string detail_;  // the first difference
};

// Attach to the master (add_observer) and to the checker (set_finding_listener); call finish()
// after the checker's finish(). Fills `out`'s tally and what the expectations need of the frames.
class RunRecorder final : public master::MasterObserver {
 public:
  RunRecorder(const Scenario& scenario, const master::SafetyReport& safety, const slave::Encoder& encoder,
              const checker::TimingChecker& checker, ScenarioResult& out, std::vector<RunSink*> sinks);
  void on_frame_start(const master::FrameResult&) override {}
  void on_sample(const master::FrameResult&, unsigned, bool, bool) override {}
  bool wants_samples() const override { return false; }
  void on_frame_end(const master::FrameResult&) override {}
  void on_result(const master::FrameResult& frame) override;
  void on_finding(const checker::Violation& finding);
  // Hands the frames still held to the sinks (every check has finished).
  void finish();

 private:
  void compare(const master::FrameResult& f);
  void settle_release();
  void flush(std::uint64_t settled);

  const Scenario& scenario_;
  const master::SafetyReport& safety_;  // the master's, for the frame that released the axis
  const slave::Encoder& encoder_;
  const checker::TimingChecker& checker_;
  ScenarioResult& out_;
  std::vector<RunSink*> sinks_;
  std::vector<sim::Time> paths_;
  PositionComparator positions_;
  std::optional<std::pair<std::uint64_t, bool>> last_good_;  // the last good read: frame, position true
  // Frames the master has finished that may still get a finding, and the findings that wait
  // for their frame.
  std::deque<master::FrameResult> waiting_;
  std::map<std::uint64_t, std::vector<checker::Violation>> findings_;
  std::uint64_t handed_out_ = 0;  // frames below this index went to the sinks
};

}  // namespace endatsim::scenarios

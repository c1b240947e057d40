#include "endatsim/scenarios/run_recorder.hpp"

#include <algorithm>

#include "endatsim/scenarios/runner.hpp"

namespace endatsim::scenarios {

void FrameTally::add(const master::FrameResult& f) {
  ++results;
  if (f.measurement) {
    ++measurement_frames;
    return;
  }
  ++outcomes[static_cast<std::size_t>(f.outcome)];
  if (f.outcome != master::FrameOutcome::Ok && failed.size() < kFailedExamples) failed.push_back(f);
  if (!first_position && f.outcome == master::FrameOutcome::Ok &&
      protocol::info(f.command).answer == protocol::AnswerFormat::Position)
    first_position = f;
}

std::vector<sim::Time> clock_paths(const Scenario& s) {
  const auto path = [](const line::LineParams& lp) {
    return lp.master.driver_delay + lp.cable_delay() + lp.encoder.receiver_delay;
  };
  std::vector<sim::Time> paths{path(s.line)};
  for (const auto& e : s.events) {
    if (e.kind != Event::Kind::SetCable) continue;
    line::LineParams lp = s.line;
    lp.cable_length_m = e.cable_length_m;
    lp.cable_delay_per_m = e.cable_delay_per_m;
    paths.push_back(path(lp));
  }
  return paths;
}

const slave::EncoderFrame* encoder_frame_of(const master::FrameResult& f, std::span<const sim::Time> paths,
                                            std::span<const slave::EncoderFrame> frames) {
  // Frames start in order: look back from the newest until every candidate start is passed.
  const sim::Time earliest = f.start + *std::min_element(paths.begin(), paths.end());
  const slave::EncoderFrame* found = nullptr;
  for (auto it = frames.rbegin(); it != frames.rend() && it->start >= earliest; ++it)
    if (std::find(paths.begin(), paths.end(), it->start - f.start) != paths.end()) found = &*it;  // the first of an instant
  return found;
}

void PositionComparator::add(const master::FrameResult& f, const slave::EncoderFrame* ef) {
  if (!detail_.empty()) return;
  ++compared_;
  // Word k > 0 of a continuous clock was latched at the falling edge after the HIGH bit.
  const bool latched = ef != nullptr && (f.word == 0 || f.word <= ef->continuous_positions.size());
  const std::uint64_t truth = !latched ? 0 : f.word == 0 ? ef->position : ef->continuous_positions[f.word - 1];
  if (!latched) detail_ = "frame " + std::to_string(f.index) + ": the encoder latched no such word";
  else if (truth != f.position)
    detail_ = "frame " + std::to_string(f.index) + ": read " + std::to_string(f.position) + ", encoder latched " +
              std::to_string(truth);
}

std::string PositionComparator::detail() const {
  if (!detail_.empty()) return detail_;
  if (compared_ == 0) return "no frame was read without error";
  return std::to_string(compared_) + " positions equal the latched ones";
}

RunRecorder::RunRecorder(const Scenario& scenario, const master::SafetyReport& safety, const slave::Encoder& encoder,
                         const checker::TimingChecker& checker, ScenarioResult& out, std::vector<RunSink*> sinks)
    : scenario_(scenario), safety_(safety), encoder_(encoder), checker_(checker), out_(out), sinks_(std::move(sinks)),
      paths_(clock_paths(scenario)) {}

void RunRecorder::on_result(const master::FrameResult& f) {
  settle_release();
  out_.tally.add(f);
  compare(f);
  if (sinks_.empty()) return;
  waiting_.push_back(f);
  flush(checker_.settled_frames());
}

void RunRecorder::compare(const master::FrameResult& f) {
  const auto& expect = scenario_.expect;
  if (f.operation < scenario_.operation_expectations.size() && scenario_.operation_expectations[f.operation])
    out_.operation_frames[f.operation] = f;  // the last frame of each operation that has an expect
  if (f.measurement || f.outcome != master::FrameOutcome::Ok ||
      protocol::info(f.command).answer != protocol::AnswerFormat::Position)
    return;
  if (expect.positions && out_.positions_read.size() < std::max<std::size_t>(expect.positions->size() + 1, 8))
    out_.positions_read.push_back(f.position);
  ++out_.positions_read_count;
  const auto* ef = encoder_frame_of(f, paths_, encoder_.frames());
  positions_.add(f, ef);  // for positions_match_encoder, and for a sweep's clean points
  if (f.word != 0 || ef == nullptr) return;
  // Frames the master took as good (no error message as it evaluates them) while the encoder had
  // an error active; the truth behind a released position, once the master says it released.
  if (ef->error_present && !f.error_detected) ++out_.undetected_errors;
  last_good_ = {f.index, ef->true_position == f.position};
}

void RunRecorder::settle_release() {
  const auto& release = safety_.release_frame;
  if (release && last_good_ && last_good_->first == *release) out_.release_position_correct = last_good_->second;
}

void RunRecorder::on_finding(const checker::Violation& v) {
  if (sinks_.empty() || !v.frame) return;
  if (*v.frame < handed_out_) {
    ++out_.late_findings;  // a check reported after saying it was done with the frame: a checker bug
    return;
  }
  findings_[*v.frame].push_back(v);
}

void RunRecorder::flush(std::uint64_t settled) {
  while (!waiting_.empty() && waiting_.front().index < settled) {
    const master::FrameResult& f = waiting_.front();
    std::vector<checker::Violation> mine;
    if (const auto it = findings_.find(f.index); it != findings_.end()) {
      mine = std::move(it->second);
      // The order a report lists them in (the checker sorts its findings by time at the end).
      std::stable_sort(mine.begin(), mine.end(), [](const auto& a, const auto& b) { return a.time < b.time; });
    }
    for (RunSink* sink : sinks_) sink->frame(out_, f, mine);
    handed_out_ = f.index + 1;
    waiting_.pop_front();
  }
  // Findings of frames the master did not record (none is expected) are dropped once settled.
  findings_.erase(findings_.begin(), findings_.lower_bound(std::min(settled, handed_out_)));
}

void RunRecorder::finish() {
  settle_release();
  out_.positions_match = PositionComparison{positions_.match(), positions_.detail()};
  flush(UINT64_MAX);
}

}  // namespace endatsim::scenarios

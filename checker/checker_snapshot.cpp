// The frame-level fast path's part of the checker (docs/performance.md): what TimingChecker holds
// between two frames, taken, compared and put back moved in time.
#include "endatsim/checker/timing_checker.hpp"

namespace endatsim::checker {
namespace {

std::uint64_t moved_index(std::uint64_t i, std::uint64_t by) { return i == UINT64_MAX ? i : i + by; }
std::optional<std::uint64_t> moved_index(std::optional<std::uint64_t> i, std::uint64_t by) {
  return i ? std::optional<std::uint64_t>(*i + by) : std::nullopt;
}
Time moved_time(Time t, Time by) { return t == Time::zero() ? t : t + by; }  // zero: not yet
std::optional<Time> moved_time(std::optional<Time> t, Time by) { return t ? std::optional<Time>(*t + by) : std::nullopt; }

}  // namespace

// Every member of TimingChecker but its configuration, what it counted, noted and kept (the
// findings, their tallies and verdicts, the worst cases), and the parts a replayable run does not
// touch (the wire decoder and its last frame with declared frames, the power-on conditions once
// judged, contentions: none may be pending).
struct TimingChecker::Snapshot {
  // Counts: a played frame adds the recorded frame's.
  std::uint64_t master_falling_edges = 0;
  std::uint64_t encoder_falling_edges = 0;
  std::vector<std::uint64_t> judged;
  // Moved with the frame: times and frame indices.
  std::deque<std::pair<std::uint64_t, FrameHeader>> pending;
  PinFrame current;
  std::optional<FrameEnd> previous_end;
  std::optional<std::uint64_t> error_handling_frame;
  std::optional<Time> busy_since;
  std::optional<std::uint64_t> awaiting_not_busy;
  std::deque<std::pair<Time, bool>> master_driven;
  std::vector<Time> master_rising;
  std::uint64_t sampled_frame = UINT64_MAX;
  std::deque<std::pair<Time, std::uint64_t>> frame_starts;
  std::optional<std::uint64_t> last_declared;
  std::optional<std::uint64_t> held_frame;
  Time last_data_rise{0};
  std::optional<Release> pending_release;
  std::optional<std::uint64_t> master_found_start_bit;
  std::deque<StartBitInFlight> start_bits_in_flight;
  std::uint64_t sample_judged_frame = UINT64_MAX;
  // The same in every frame of a steady run.
  bool in_frame = false, busy_reported = false, awaiting_known = false, floating_reported = false,
       sampling_reported = false, last_frame_was_measurement = false, t_d_stale = false, measured = false,
       unmeasured_reported = false, declared_running = false, wire_request_seen = false, fe1_lost = false,
       released = false, driving = false, driven_low = false, low_at_last_rise = false,
       unmeasured_on_wires_reported = false, measurements_may_precede = false, recovery_checked = false,
       mode_decided = false, wires_only = false, measurement_seen = false;
  unsigned start_clock = 0, word_start_clock = 0, word = 0, low_clock = 0;
  ActivatedSettings settings{false};
  DelayMeasurements delay_measurements;
  std::optional<std::uint64_t> first_frame;

  bool operator==(const Snapshot&) const = default;

  // This state moved by `dt` and `di`, its counts left as they are.
  Snapshot moved(Time dt, std::uint64_t di) const {
    Snapshot s = *this;
    for (auto& pending_frame : s.pending) pending_frame.second.index += di;  // (empty: replayable())
    s.current.header.index = in_frame ? current.header.index + di : current.header.index;
    s.current.fe1 = moved_time(current.fe1, dt);
    for (Time& t : s.current.rising) t += dt;
    for (Time& t : s.current.falling) t += dt;
    if (s.previous_end) {
      s.previous_end->last_rise += dt;
      s.previous_end->index += di;
    }
    s.error_handling_frame = moved_index(error_handling_frame, di);
    s.busy_since = moved_time(busy_since, dt);
    s.awaiting_not_busy = moved_index(awaiting_not_busy, di);
    for (auto& d : s.master_driven) d.first += dt;
    for (Time& t : s.master_rising) t += dt;
    s.sampled_frame = moved_index(sampled_frame, di);
    for (auto& [t, index] : s.frame_starts) {
      t += dt;
      index += di;
    }
    s.last_declared = moved_index(last_declared, di);
    s.held_frame = moved_index(held_frame, di);
    s.last_data_rise = moved_time(last_data_rise, dt);
    if (s.pending_release) s.pending_release->at += dt;
    s.master_found_start_bit = moved_index(master_found_start_bit, di);
    for (StartBitInFlight& b : s.start_bits_in_flight) {
      b.due += dt;
      b.carried_at += dt;
      b.frame += di;
    }
    s.sample_judged_frame = moved_index(sample_judged_frame, di);
    return s;
  }
  // The state without its counts, to compare two frames' states.
  Snapshot without_counts() const {
    Snapshot s = *this;
    s.master_falling_edges = s.encoder_falling_edges = 0;
    s.judged.clear();
    return s;
  }
};

// No declared frame on its way to the encoder pins: those wait for a count of falling edges there,
// which a frame played again would have to move too.
bool TimingChecker::replayable() const {
  return mode_decided_ && !wires_only_ && pending_.empty() && contentions_.empty() && !power_on_.due() && !finished_ &&
         !capture_ && !run_cut_at_ && !frozen_mark_ && !contention_recorded_;
}

std::shared_ptr<const TimingChecker::Snapshot> TimingChecker::snapshot() const {
  auto s = std::make_shared<Snapshot>();
  s->master_falling_edges = master_falling_edges_;
  s->encoder_falling_edges = encoder_falling_edges_;
  s->judged = judged_;
  s->pending = pending_;
  s->current = current_;
  s->previous_end = previous_end_;
  s->error_handling_frame = error_handling_frame_;
  s->busy_since = busy_since_;
  s->awaiting_not_busy = awaiting_not_busy_;
  s->master_driven = master_driven_;
  s->master_rising = master_rising_;
  s->sampled_frame = sampled_frame_;
  s->frame_starts = frame_starts_;
  s->last_declared = last_declared_;
  s->held_frame = held_frame_;
  s->last_data_rise = last_data_rise_;
  s->pending_release = pending_release_;
  s->master_found_start_bit = master_found_start_bit_;
  s->start_bits_in_flight = start_bits_in_flight_;
  s->sample_judged_frame = sample_judged_frame_;
  s->in_frame = in_frame_;
  s->busy_reported = busy_reported_;
  s->awaiting_known = awaiting_known_;
  s->floating_reported = floating_reported_;
  s->sampling_reported = sampling_reported_;
  s->last_frame_was_measurement = last_frame_was_measurement_;
  s->t_d_stale = t_d_stale_;
  s->measured = measured_;
  s->unmeasured_reported = unmeasured_reported_;
  s->declared_running = declared_running_;
  s->wire_request_seen = wire_request_seen_;
  s->fe1_lost = fe1_lost_;
  s->released = released_;
  s->driving = driving_;
  s->driven_low = driven_low_;
  s->low_at_last_rise = low_at_last_rise_;
  s->unmeasured_on_wires_reported = unmeasured_on_wires_reported_;
  s->measurements_may_precede = measurements_may_precede_;
  s->recovery_checked = recovery_checked_;
  s->mode_decided = mode_decided_;
  s->wires_only = wires_only_;
  s->measurement_seen = measurement_seen_;
  s->start_clock = start_clock_;
  s->word_start_clock = word_start_clock_;
  s->word = word_;
  s->low_clock = low_clock_;
  s->settings = settings_;
  s->delay_measurements = delay_measurements_;
  s->first_frame = first_frame_;
  return s;
}

bool TimingChecker::same_moved(const Snapshot& earlier, const Snapshot& later, Time shift, std::uint64_t index_shift) {
  return earlier.without_counts().moved(shift, index_shift) == later.without_counts();
}

bool TimingChecker::same_counts(const Snapshot& start0, const Snapshot& end0, const Snapshot& start1, const Snapshot& end1) {
  if (end0.master_falling_edges - start0.master_falling_edges != end1.master_falling_edges - start1.master_falling_edges ||
      end0.encoder_falling_edges - start0.encoder_falling_edges != end1.encoder_falling_edges - start1.encoder_falling_edges)
    return false;
  for (std::size_t row = 0; row < end0.judged.size(); ++row)
    if (end0.judged[row] - start0.judged[row] != end1.judged[row] - start1.judged[row]) return false;
  return true;
}

void TimingChecker::restore(const Snapshot& start, const Snapshot& end, Time shift, std::uint64_t index_shift) {
  const Snapshot s = end.moved(shift, index_shift);
  master_falling_edges_ += end.master_falling_edges - start.master_falling_edges;
  encoder_falling_edges_ += end.encoder_falling_edges - start.encoder_falling_edges;
  for (std::size_t row = 0; row < judged_.size(); ++row) judged_[row] += end.judged[row] - start.judged[row];
  pending_ = s.pending;
  current_ = s.current;
  previous_end_ = s.previous_end;
  error_handling_frame_ = s.error_handling_frame;
  busy_since_ = s.busy_since;
  awaiting_not_busy_ = s.awaiting_not_busy;
  master_driven_ = s.master_driven;
  master_rising_ = s.master_rising;
  sampled_frame_ = s.sampled_frame;
  frame_starts_ = s.frame_starts;
  last_declared_ = s.last_declared;
  held_frame_ = s.held_frame;
  last_data_rise_ = s.last_data_rise;
  pending_release_ = s.pending_release;
  master_found_start_bit_ = s.master_found_start_bit;
  start_bits_in_flight_ = s.start_bits_in_flight;
  sample_judged_frame_ = s.sample_judged_frame;
  in_frame_ = s.in_frame;
  busy_reported_ = s.busy_reported;
  awaiting_known_ = s.awaiting_known;
  floating_reported_ = s.floating_reported;
  sampling_reported_ = s.sampling_reported;
  last_frame_was_measurement_ = s.last_frame_was_measurement;
  t_d_stale_ = s.t_d_stale;
  measured_ = s.measured;
  unmeasured_reported_ = s.unmeasured_reported;
  declared_running_ = s.declared_running;
  wire_request_seen_ = s.wire_request_seen;
  fe1_lost_ = s.fe1_lost;
  released_ = s.released;
  driving_ = s.driving;
  driven_low_ = s.driven_low;
  low_at_last_rise_ = s.low_at_last_rise;
  unmeasured_on_wires_reported_ = s.unmeasured_on_wires_reported;
  measurements_may_precede_ = s.measurements_may_precede;
  recovery_checked_ = s.recovery_checked;
  mode_decided_ = s.mode_decided;
  wires_only_ = s.wires_only;
  measurement_seen_ = s.measurement_seen;
  start_clock_ = s.start_clock;
  word_start_clock_ = s.word_start_clock;
  word_ = s.word;
  low_clock_ = s.low_clock;
  settings_ = s.settings;
  delay_measurements_ = s.delay_measurements;
  first_frame_ = s.first_frame;
}

void TimingChecker::replay(const sim::TapeItem& item, const std::vector<Violation>& findings, Time shift,
                           std::uint64_t index_shift) {
  report(moved(findings.at(item.value), shift, index_shift), std::nullopt);
}

}  // namespace endatsim::checker

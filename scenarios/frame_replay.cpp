#include "endatsim/scenarios/frame_replay.hpp"

#include <algorithm>

#include "endatsim/sim/signal.hpp"

namespace endatsim::scenarios {
namespace {

// Recordings made again for the checker's part before a frame is played with the checker shown it.
constexpr unsigned kCheckerAttempts = 4;
// A moving axis: frames are recorded only while its position will stand for this many more
// frames, enough to confirm recordings of both kinds and play some. Recording costs as much as
// running a frame again, and a position that changes sooner would leave nothing to play.
constexpr std::int64_t kRecordingHorizon = 5;

// The same request apart from the frame's index.
bool same_request(master::FrameRequest a, const master::FrameRequest& b) {
  a.index = b.index;
  return a == b;
}

}  // namespace

std::string_view to_string(Engine e) {
  switch (e) {
    case Engine::Event: return "event";
    case Engine::Auto: return "auto";
    case Engine::Fast: return "fast";
  }
  return "?";
}

std::optional<Engine> engine_from(std::string_view name) {
  for (const Engine e : {Engine::Event, Engine::Auto, Engine::Fast})
    if (to_string(e) == name) return e;
  return std::nullopt;
}

FrameReplay::FrameReplay(sim::Kernel& kernel, line::Line& line, master::Master& master, slave::Encoder& encoder,
                         const EventDriver& events, const Room& room, MasterDeclarations& declarations,
                         sim::VcdWriter* vcd)
    : kernel_(kernel), line_(line), master_(master), encoder_(encoder), events_(events), room_(room),
      declarations_(declarations), checker_(declarations.checker()), vcd_(vcd) {
  master_.set_shortcut(this);
}

FrameReplay::~FrameReplay() {
  if (recording_) kernel_.record_to(nullptr);
  master_.set_shortcut(nullptr);
}

// What must hold of the run for a frame to be recorded or played: a master clock without jitter
// (its generator would be drawn from), no measurement, not the operation's last frame (what
// follows it is paced differently), a mode command without 8 + 16 bits (a 2.1 payload or a 2.2
// command supplement: what the encoder does with them, a selection, a memory access, an error
// reset, is not played, and a 2.1 payload frame may wait t_b before it starts), an encoder whose
// frame changes nothing, and no scenario event still to come that a frame or a clock edge sets off.
bool FrameReplay::steady(const master::FrameRequest& request) const {
  const protocol::ModeCommandInfo& command = protocol::info(request.command);
  return command.payload_bits == 0 && !command.supplement && master_.params().jitter == Time::zero() &&
         !request.measurement && !master_.measuring() &&
         master_.frames_left() > 1 && encoder_.frame_invariant() && events_.quiet_from(request.index) &&
         !kernel_.work_pending();
}

bool FrameReplay::replayed(const master::FrameRequest& request) {
  // Recordings are played only while every frame since they were confirmed was recorded alike or
  // played, and nothing else ran between the frames (a scenario event, a cable change): the
  // world is then the one they were made in.
  bool unbroken = false;
  if (recording_) unbroken = close_recording();
  else if (played_) unbroken = kernel_.events_processed() == events_after_play_;
  played_ = false;
  if (!unbroken) ++epoch_;
  const bool strobe = master_.sample_strobe().read();
  // The time since the frame before began: what the encoder's recovery and the checker's rows
  // between frames see. The first and last frames of an operation are paced apart from the rest.
  const std::optional<Time> gap = last_start_ ? std::optional<Time>(kernel_.now() - *last_start_) : std::nullopt;
  last_start_ = kernel_.now();
  if (!gap || !steady(request)) return false;
  auto& last = last_[strobe ? 1 : 0];
  // A recording whose checker part did not repeat yet is made again a few times: the checker
  // settles a frame or two after the models (it judges a frame when the next one begins).
  const bool checker_pending = last && !last->checker_confirmed && last->checker_attempts < kCheckerAttempts;
  if (unbroken && last && last->epoch == epoch_ && !checker_pending && last->gap == *gap && may_play(*last, request)) {
    if (!last->playback) last->playback = compile(*last);
    play(*last, request);
    played_ = true;
    events_after_play_ = kernel_.events_processed() + 1;  // this event, counted as it returns
    return true;
  }
  if (!encoder_.holds_position(kernel_.now(), kernel_.now() + kRecordingHorizon * *gap)) return false;
  recording_.emplace();
  // A recording is as long as the one before it of its kind, most likely.
  if (last) recording_->tape.items.reserve(last->tape.items.size());
  recording_->request = request;
  recording_->start = kernel_.now();
  recording_->strobe = strobe;
  recording_->gap = *gap;
  recording_->contentions = line_.contentions_seen();
  recording_->ignored_edges = encoder_.ignored_clock_edges();
  recording_->event_actions = events_.actions();
  recording_->vcd_quiet = vcd_ != nullptr && vcd_->quiet();
  if (checker_.replayable()) recording_->checker_start = checker_.snapshot();
  kernel_.record_to(&recording_->tape);
  return false;
}

// The frame that was recorded ends where the next one begins.
bool FrameReplay::close_recording() {
  kernel_.record_to(nullptr);
  Recording r = std::move(*recording_);
  recording_.reset();
  // The events up to here, less this one, which the kernel counts as it returns.
  r.tape.events = kernel_.events_since_recording();
  r.frames = master_.engine().take_recorded_frames();
  r.encoder_frames = encoder_.take_recorded_frames();
  r.findings = checker_.take_recorded_findings();
  if (r.checker_start && checker_.replayable()) r.checker_end = checker_.snapshot();
  // One frame at the encoder, read Ok, no contention, no clock edge the encoder did not take (t_R),
  // no scenario event acting inside it (even one that changed nothing is an event the frame ran).
  const bool clean = line_.contentions_seen() == r.contentions && encoder_.ignored_clock_edges() == r.ignored_edges &&
                     events_.actions() == r.event_actions &&
                     r.encoder_frames.size() == 1 && !r.frames.empty() && r.frames.back().outcome == master::FrameOutcome::Ok;
  if (!clean) {
    last_ = {};
    return false;
  }
  auto& slot = last_[r.strobe ? 1 : 0];
  if (slot) {
    const Recording& p = *slot;
    const Time shift = r.start - p.start;
    const std::uint64_t index_shift = r.request.index - p.request.index;
    bool same = same_request(p.request, r.request) && p.gap == r.gap && p.tape.events == r.tape.events &&
                p.tape.items.size() == r.tape.items.size() && p.frames.size() == r.frames.size();
    for (std::size_t i = 0; same && i < p.tape.items.size(); ++i) {
      sim::TapeItem moved_item = p.tape.items[i];
      moved_item.at += shift;
      same = moved_item == r.tape.items[i];
    }
    for (std::size_t i = 0; same && i < p.frames.size(); ++i)
      same = master::moved(p.frames[i], shift, index_shift) == r.frames[i];
    same = same && slave::moved(p.encoder_frames.front(), shift) == r.encoder_frames.front();
    r.confirmed = same;
    r.checker_confirmed = same && same_checker_part(p, r, shift, index_shift);
    r.checker_attempts = r.checker_confirmed ? 0 : p.checker_attempts + 1;
  }
  r.epoch = epoch_;
  const bool confirmed = r.confirmed;
  slot = std::move(r);
  return confirmed;
}

bool FrameReplay::same_checker_part(const Recording& p, const Recording& r, Time shift, std::uint64_t index_shift) const {
  using checker::TimingChecker;
  if (!p.checker_end || !r.checker_end || p.findings.size() != r.findings.size()) return false;
  if (!TimingChecker::same_moved(*p.checker_start, *r.checker_start, shift, index_shift) ||
      !TimingChecker::same_moved(*p.checker_end, *r.checker_end, shift, index_shift) ||
      !TimingChecker::same_counts(*p.checker_start, *p.checker_end, *r.checker_start, *r.checker_end))
    return false;
  for (std::size_t i = 0; i < p.findings.size(); ++i)  // its words may name a frame or a time
    if (!(checker::moved(p.findings[i], shift, index_shift) == r.findings[i])) return false;
  return true;
}

bool FrameReplay::may_play(const Recording& r, const master::FrameRequest& request) const {
  if (!r.confirmed || !same_request(r.request, request) || r.tape.items.empty()) return false;
  // The last thing the frame did is on the tape, whether it is played or stands at the end.
  const Time end = kernel_.now() + (r.tape.items.back().at - r.start);
  const std::optional<Time> next = kernel_.next_event_time();
  if (prepares_vcd(r) && !vcd_->quiet()) return false;  // its first time step is prepared as it began
  if (!encoder_.latches_again(r.encoder_frames.front(), kernel_.now() - r.start, end)) return false;  // a moving axis
  return (!next || *next > end) && end <= kernel_.run_until() && room_.for_frame(r.tape.events, r.frames.size() + r.encoder_frames.size() + r.findings.size());
}

// What the VCD writer writes for the recording is prepared when the writer is the only action at
// the end of a time step and had nothing waiting when the recording began.
bool FrameReplay::prepares_vcd(const Recording& r) const {
  return vcd_ != nullptr && r.vcd_quiet && kernel_.step_end_actions() == 1;
}

FrameReplay::Playback FrameReplay::compile(const Recording& r) const {
  using K = sim::TapeItem::Kind;
  Playback p;
  const bool step_ends = kernel_.step_end_actions() != 0;
  if (prepares_vcd(r)) p.vcd = vcd_->prepare(r.tape, r.start);
  std::uint32_t vcd_steps = 0;
  // With the checker put in place, what only it observes is not played, nor the sampling
  // instants if no one else wants them; without, its findings come from itself.
  const void* checker = &checker_;
  const void* engine = &master_.engine();
  const bool samples = !r.checker_confirmed || master_.engine().samples_wanted(&declarations_);
  // The monitors not shown the frame: the checker put in place, the VCD writer's prepared lines.
  const auto unseen = [&](const void* monitor) {
    return (r.checker_confirmed && monitor == checker) || (p.vcd && vcd_->is_probe(monitor));
  };
  std::vector<std::size_t> final_of;  // per signal seen, its place in p.finals
  std::vector<const void*> seen;
  for (std::size_t k = 0; k < r.tape.items.size(); ++k) {
    const sim::TapeItem& i = r.tape.items[k];
    const Time at = i.at - r.start;
    switch (i.kind) {
      case K::Commit: {
        // Every signal is a Signal (SignalBase only spares the kernel its header).
        auto* signal = const_cast<sim::Signal*>(static_cast<const sim::Signal*>(static_cast<const sim::SignalBase*>(i.who)));
        if (signal->observed(unseen)) {
          p.items.push_back({at, Playback::Kind::Commit, 0, signal, i.value});
          break;
        }
        const auto it = std::find(seen.begin(), seen.end(), i.who);
        if (it == seen.end()) {
          seen.push_back(i.who);
          final_of.push_back(p.finals.size());
          p.finals.push_back({signal, i.value != 0, at, 1});
        } else {
          Playback::Final& f = p.finals[final_of[static_cast<std::size_t>(it - seen.begin())]];
          f.value = i.value != 0;
          f.last_change = at;
          ++f.changes;
        }
        break;
      }
      case K::Monitor: {
        const void* listener = static_cast<const sim::SignalBase*>(i.who)->listener_of(i.index);
        if (r.checker_confirmed && listener == checker) break;
        if (p.vcd && k < p.vcd->covered && vcd_->is_probe(listener)) break;  // in the prepared lines
        p.items.push_back({at, Playback::Kind::Monitor, i.index, i.who, i.value});
        break;
      }
      case K::StepEnd:
        if (!p.vcd) {
          if (step_ends) p.items.push_back({at, Playback::Kind::StepEnd, 0, nullptr, 0});
        } else if (!p.items.empty() && p.items.back().kind == Playback::Kind::VcdSteps) {
          ++p.items.back().value;
        } else {
          p.items.push_back({at, Playback::Kind::VcdSteps, vcd_steps, nullptr, 1});
        }
        ++vcd_steps;
        break;
      case K::Model:
        if (i.who == checker && !r.checker_confirmed) break;
        if (i.who == engine && !samples && i.index == static_cast<std::uint32_t>(master::FrameEngine::Note::Sample)) break;
        p.items.push_back({at, Playback::Kind::Model, i.index, i.who, i.value});
        break;
    }
  }
  p.end = r.tape.items.back().at - r.start;
  return p;
}

void FrameReplay::play(const Recording& r, const master::FrameRequest& request) {
  const Time start = kernel_.now();
  const Time shift = start - r.start;
  const std::uint64_t index_shift = request.index - r.request.index;
  master::FrameEngine& engine = master_.engine();
  declarations_.mute(r.checker_confirmed);
  for (const Playback::Item& item : r.playback->items) {
    kernel_.replay_time(start + item.at);
    switch (item.kind) {
      case Playback::Kind::Commit: static_cast<sim::Signal*>(const_cast<void*>(item.who))->replay_commit(item.value); break;
      case Playback::Kind::Monitor:
        static_cast<const sim::SignalBase*>(item.who)->replay_monitor(item.index, item.value);
        break;
      case Playback::Kind::StepEnd: kernel_.replay_step_end(); break;
      case Playback::Kind::VcdSteps: vcd_->play_steps(*r.playback->vcd, item.index, item.index + item.value, start); break;
      case Playback::Kind::Model: {
        const sim::TapeItem note{sim::TapeItem::Kind::Model, start + item.at, item.who, item.index, item.value};
        if (item.who == &engine) engine.replay(note, r.frames, shift, index_shift);
        else if (item.who == &checker_) checker_.replay(note, r.findings, shift, index_shift);
        else encoder_.replay(note, r.encoder_frames, shift);
        break;
      }
    }
  }
  for (const Playback::Final& f : r.playback->finals) f.signal->replay_final(f.value, start + f.last_change, f.changes);
  if (r.playback->vcd) vcd_->play_end(*r.playback->vcd);
  declarations_.mute(false);
  if (r.checker_confirmed) checker_.restore(*r.checker_start, *r.checker_end, shift, index_shift);
  kernel_.replay_time(start + r.playback->end);  // where the frame's last event was
  kernel_.replay_done(kernel_.now());
  kernel_.replay_events(r.tape.events - 1);
  ++replayed_;
}

}  // namespace endatsim::scenarios

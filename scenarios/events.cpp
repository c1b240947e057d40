#include "endatsim/scenarios/events.hpp"

#include "endatsim/scenarios/event_kinds.hpp"

#include <algorithm>

namespace endatsim::scenarios {
namespace {

using K = Event::Kind;
using line::ObservationPoint;

std::size_t side(ObservationPoint end) { return end == ObservationPoint::MasterPins ? 0 : 1; }

bool counts_clock_edges(const Event& e) { return (e.frame && e.clock > 0) || e.kind == K::RandomBitErrors; }

ObservationPoint edge_end(const Event& e) {
  const bool line_fault = e.kind == K::BitFlip || e.kind == K::Glitch || e.kind == K::Stuck ||
                          e.kind == K::RandomBitErrors || e.kind == K::LateDriverRelease;
  return line_fault ? e.end : ObservationPoint::MasterPins;
}

}  // namespace

EventDriver::EventDriver(sim::Kernel& kernel, line::Line& line, slave::Encoder& encoder, master::Master* master,
                         checker::TimingChecker& checker, const std::vector<Event>& events, std::uint64_t seed,
                         Time bit_period)
    : kernel_(kernel), line_(line), encoder_(encoder), master_(master), checker_(checker), events_(events),
      period_(bit_period), rng_(seed ^ 0x5EED'FA17'0000'0005ULL), acted_(events.size(), false) {
  bool listen[2] = {false, false};
  for (std::size_t i = 0; i < events.size(); ++i) {
    if (events[i].at) kernel.schedule_at(*events[i].at + events[i].offset, sim::bind<&EventDriver::apply>(this, i));
    if (counts_clock_edges(events[i])) listen[side(edge_end(events[i]))] = true;
  }
  if (listen[0]) line.pins(ObservationPoint::MasterPins).clock.on_change(sim::bind<&EventDriver::on_master_clock>(this));
  if (listen[1]) line.pins(ObservationPoint::EncoderPins).clock.on_change(sim::bind<&EventDriver::on_encoder_clock>(this));
  if (master != nullptr) master->add_observer(this);
  counts_edges_ = listen[0] || listen[1];
}

bool EventDriver::quiet_from(std::uint64_t frame) const {
  return !counts_edges_ && std::none_of(events_.begin(), events_.end(), [&](const Event& e) { return e.frame && *e.frame >= frame; });
}

void EventDriver::frame_started(std::uint64_t index) {
  for (std::size_t i = 0; i < events_.size(); ++i) {
    const Event& e = events_[i];
    if (!e.frame || *e.frame != index) continue;
    if (e.clock == 0) kernel_.schedule(e.offset, sim::bind<&EventDriver::apply>(this, i));
    else armed_[side(edge_end(e))].push_back({i});
  }
}

void EventDriver::on_rising_edge(ObservationPoint end, std::uint64_t level) {
  if (level == 0) return;
  auto& armed = armed_[side(end)];
  for (auto& a : armed)
    if (++a.edges == events_[a.event].clock) kernel_.schedule(events_[a.event].offset, sim::bind<&EventDriver::apply>(this, a.event));
  std::erase_if(armed, [this](const Armed& a) { return a.edges >= events_[a.event].clock; });
  // A bit error: DATA inverted for one clock period covers exactly one sampling instant.
  for (std::size_t i : random_[side(end)]) {
    const double rate = events_[i].rate;
    const auto threshold = rate >= 1.0 ? UINT64_MAX : static_cast<std::uint64_t>(rate * 18446744073709551616.0);
    if (rng_() >= threshold) continue;
    line_.invert(line::Wire::Data, end, period_);
    ++random_bit_errors_;
    ++actions_;
  }
}

std::vector<EventNotActed> EventDriver::not_acted() const {
  std::vector<EventNotActed> out;
  for (std::size_t i = 0; i < acted_.size(); ++i) {
    if (acted_[i]) continue;
    const Event& e = events_[i];
    EventNotActed n{i, "", ""};
    for (const auto& k : event_kinds())
      if (k.kind == e.kind) n.kind = std::string(k.key);
    if (e.at) n.when = "at " + sim::format_time(*e.at);
    else if (e.frame) n.when = "frame " + std::to_string(*e.frame) + (e.clock != 0 ? ", clock " + std::to_string(e.clock) : "");
    if (e.offset != Time::zero()) n.when += " + " + sim::format_time(e.offset);
    out.push_back(std::move(n));
  }
  return out;
}

void EventDriver::apply(std::uint64_t index) {
  ++actions_;
  acted_[index] = true;
  const Event& e = events_[index];
  if (e.kind >= K::ErrorSources) apply_to_encoder(e);
  else apply_to_line(e, index);
}

void EventDriver::apply_to_line(const Event& e, std::uint64_t index) {
  switch (e.kind) {
    case K::SetCable:
      line_.set_cable(e.cable_length_m, e.cable_delay_per_m);
      checker_.on_line_change();
      if (master_ != nullptr) master_->line_changed();
      break;
    case K::BitFlip:
      line_.invert(e.wire, e.end, e.width > Time::zero() ? e.width : period_);
      break;
    case K::Glitch:
      line_.invert(e.wire, e.end, e.width);
      break;
    case K::Stuck:
      line_.stick(e.wire, e.end, e.level != 0);
      if (e.duration) kernel_.schedule(*e.duration, sim::bind<&EventDriver::end_of>(this, index));
      break;
    case K::RandomBitErrors:
      random_[side(e.end)].push_back(index);
      if (e.duration) kernel_.schedule(*e.duration, sim::bind<&EventDriver::end_of>(this, index));
      break;
    case K::LateDriverRelease:
      line_.set_driver_disable_delay(e.end, e.width);
      break;
    case K::LossOfFailsafe:
      line_.set_failsafe_level(e.level != 0);
      break;
    default:
      break;
  }
}

void EventDriver::apply_to_encoder(const Event& e) {
  switch (e.kind) {
    case K::ErrorSources:
      encoder_.set_error_sources(e.errors, e.warnings);
      break;
    case K::MemoryAccessTime:
      encoder_.set_memory_access_times(e.t_ac_read, e.t_ac_write);
      break;
    case K::TCal:
      encoder_.set_t_cal(e.t_cal);
      break;
    case K::PowerInterruption:
      encoder_.power_interruption(*e.duration);
      checker_.on_line_change();  // 2.1.2: "after power interruption" as after a change of the line
      kernel_.schedule(*e.duration, sim::bind<&EventDriver::supply_back>(this));
      // The drive's supply monitor: the encoder is back after the dip and its run-up.
      kernel_.schedule(*e.duration + encoder_.params().startup_time, sim::bind<&EventDriver::power_back>(this));
      break;
    case K::CorruptWord:
      encoder_.corrupt_word(e.selection, e.address, e.xor_mask);
      break;
    case K::ProbeTrigger:
      encoder_.set_probe_deflected(true);
      kernel_.schedule(*e.duration, sim::bind<&EventDriver::release_probe>(this));
      break;
    case K::StuckErrorMessages:
      encoder_.set_stuck_error_messages(e.error_message_1_stuck, e.error_message_2_stuck);
      break;
    case K::Slip:
      encoder_.slip(e.steps);
      break;
    case K::Position2Fault:
      encoder_.set_position2_fault(e.steps);
      break;
    case K::SensorValues:
      encoder_.set_sensor_values(e.sensors);
      break;
    default:
      break;
  }
}

void EventDriver::end_of(std::uint64_t index) {
  ++actions_;
  const Event& e = events_[index];
  if (e.kind == K::Stuck) line_.stick(e.wire, e.end, std::nullopt);
  if (e.kind == K::RandomBitErrors) std::erase(random_[side(e.end)], index);
}

}  // namespace endatsim::scenarios

#include "endatsim/line/line.hpp"

#include <array>
#include <cmath>
#include <algorithm>
#include <deque>
#include <stdexcept>
#include <string>

namespace endatsim::line {

using sim::Signal;
using sim::TransportDelay;

Time LineParams::cable_delay() const {
  return Time{std::llround(cable_length_m * static_cast<double>(cable_delay_per_m.count()))};
}

namespace {

constexpr std::array<std::string_view, 2> kFailsafeLevels{"high", "low"};

const std::array kLine{
    sim::Parameter<LineParams>{"cable_length_m",
                               sim::NumberField<LineParams>{&LineParams::cable_length_m, " m"}, 0,
                               static_cast<std::int64_t>(LineParams::kMaxCableLengthM), "2.1.2",
                               "The cable's length (up to 300 m on request).", true},
    sim::Parameter<LineParams>{"cable_delay_per_m", &LineParams::cable_delay_per_m, 0,
                               LineParams::kMaxCableDelayPerM.count(), "2.3.2 note 2",
                               "One-way propagation delay per metre (the 0.01 us/m of t_D is the round trip)."},
    sim::Parameter<LineParams>{"failsafe_level",
                               sim::ChoiceField<LineParams>{kFailsafeLevels,
                                                            [](const LineParams& p) -> std::size_t { return p.failsafe_level ? 0 : 1; },
                                                            [](LineParams& p, std::size_t i) { p.failsafe_level = i == 0; }},
                               0, 0, "", "What a receiver reads on undriven DATA (true fail-safe receivers: high)."},
};

const std::array kTransceiver{
    sim::Parameter<TransceiverParams>{"driver_delay", &TransceiverParams::driver_delay, 0,
                                      LineParams::kMaxTransceiverDelay.count(), "", "Logic input to the level on the pins."},
    sim::Parameter<TransceiverParams>{"enable_delay", &TransceiverParams::enable_delay, 0,
                                      LineParams::kMaxTransceiverDelay.count(), "", "Driver enable to the pins driven."},
    sim::Parameter<TransceiverParams>{"disable_delay", &TransceiverParams::disable_delay, 0,
                                      LineParams::kMaxTransceiverDelay.count(), "",
                                      "Driver disable to the pins released (high impedance)."},
    sim::Parameter<TransceiverParams>{"receiver_delay", &TransceiverParams::receiver_delay, 0,
                                      LineParams::kMaxTransceiverDelay.count(), "", "The level on the pins to the logic output."},
};

}  // namespace

std::span<const sim::Parameter<LineParams>> line_parameters() { return kLine; }
std::span<const sim::Parameter<TransceiverParams>> transceiver_parameters() { return kTransceiver; }

void LineParams::validate() const {
  if (auto why = sim::first_out_of_range(line_parameters(), *this, "line")) throw std::invalid_argument(*why);
  for (const auto& [name, t] : {std::pair{"master_transceiver", &master}, {"encoder_transceiver", &encoder}})
    if (auto why = sim::first_out_of_range(transceiver_parameters(), *t, std::string("line ") + name))
      throw std::invalid_argument(*why);
}

std::string_view to_string(ObservationPoint p) {
  return p == ObservationPoint::MasterPins ? "master pins" : "encoder pins";
}

// The resolvers' way to the line's contentions (log and listeners).
class ContentionLog {
 public:
  explicit ContentionLog(Line& line) : line_(line) {}
  std::uint64_t begin(ObservationPoint where, bool between_encoders) {
    return line_.begin_contention(where, between_encoders);
  }
  void end(std::uint64_t sequence) { line_.end_contention(sequence); }

 private:
  Line& line_;
};

// One end of the DATA pair: the local driver is seen at once, the remote one after the cable.
class PinResolver {
 public:
  PinResolver(ObservationPoint where, Signal& local_en, Signal& local_level, Signal& remote_en,
              Signal& remote_level, Signal& pin, Signal& driven, ContentionLog log, bool& failsafe)
      : where_(where), local_en_(local_en), local_level_(local_level), remote_en_(remote_en),
        remote_level_(remote_level), pin_(pin), driven_(driven), log_(log), failsafe_(failsafe) {
    for (Signal* s : {&local_en, &local_level, &remote_en, &remote_level})
      s->on_change(sim::bind<&PinResolver::resolve>(this));
  }

  void resolve() {
    const bool local = local_en_.read();
    const bool remote = remote_en_.read();
    const bool both = local && remote;
    if (both && !open_) {
      open_ = log_.begin(where_, false);
    } else if (!both && open_) {
      log_.end(*open_);
      open_.reset();
    }
    driven_.write(local || remote);
    // During contention the near driver dominates its own end of the pair.
    if (local) pin_.write(local_level_.read());
    else if (remote) pin_.write(remote_level_.read());
    else pin_.write(failsafe_);
  }

 private:
  ObservationPoint where_;
  Signal& local_en_;
  Signal& local_level_;
  Signal& remote_en_;
  Signal& remote_level_;
  Signal& pin_;
  Signal& driven_;
  ContentionLog log_;
  std::optional<std::uint64_t> open_;  // the contention going on here
  bool& failsafe_;
};

// Faults at one end's pins: the level there is the line's level, inverted while a
// glitch lasts, or stuck at a level. The fault stays at that end (noise coupled into one
// connector): the cable carries the undisturbed level.
class PinFault {
 public:
  PinFault(sim::Kernel& kernel, Signal& line_level, Signal& pin) : kernel_(kernel), in_(line_level), out_(pin) {
    line_level.on_change(sim::bind<&PinFault::resolve>(this));
  }
  void invert_for(Time width) {
    inverted_until_ = std::max(inverted_until_, kernel_.now() + width);
    resolve();
    kernel_.schedule(width, sim::bind<&PinFault::resolve>(this));
  }
  void stick(std::optional<bool> level) {
    stuck_ = level;
    resolve();
  }
  void resolve() {
    bool v = in_.read() != (kernel_.now() < inverted_until_);
    if (stuck_) v = *stuck_;
    out_.write(v);
  }

 private:
  sim::Kernel& kernel_;
  Signal& in_;
  Signal& out_;
  Time inverted_until_{0};
  std::optional<bool> stuck_;
};

// The encoder end of DATA with several encoders on the bus (2.10): their drivers, after their
// driver delays, resolve into the one driver the cable and the master see.
class EncoderBus {
 public:
  EncoderBus(Signal& drive_en, Signal& drive_level, ContentionLog log)
      : drive_en_(drive_en), drive_level_(drive_level), log_(log) {}
  void add(Signal& en, Signal& level) {
    taps_.emplace_back(&en, &level);
    en.on_change(sim::bind<&EncoderBus::resolve>(this));
    level.on_change(sim::bind<&EncoderBus::resolve>(this));
    resolve();
  }
  void resolve() {
    unsigned enabled = 0;
    bool level = true;  // two drivers that disagree: the LOW one wins (wired, undefined in RS-485)
    for (const auto& [en, lv] : taps_) {
      if (!en->read()) continue;
      ++enabled;
      level = level && lv->read();
    }
    if (enabled > 1 && !open_) {
      open_ = log_.begin(ObservationPoint::EncoderPins, true);
    } else if (enabled <= 1 && open_) {
      log_.end(*open_);
      open_.reset();
    }
    drive_en_.write(enabled > 0);
    drive_level_.write(enabled > 0 && level);
  }

 private:
  Signal& drive_en_;
  Signal& drive_level_;
  ContentionLog log_;
  std::vector<std::pair<Signal*, Signal*>> taps_;
  std::optional<std::uint64_t> open_;  // the contention going on between encoders
};

// One encoder's transceiver on the bus.
struct EncoderTap {
  EncoderTap(sim::Kernel& k, const LineParams& p, const std::string& n)
      : data_out(k, "e_data_out_" + n, false), data_enable(k, "e_data_enable_" + n, false),
        level(k, "e_tap_level_" + n, false), en(k, "e_tap_en_" + n, false),
        level_driver(k, data_out, level, p.encoder.driver_delay),
        en_driver(k, data_enable, en, p.encoder.enable_delay, p.encoder.disable_delay) {}
  Signal data_out, data_enable, level, en;
  TransportDelay level_driver, en_driver;
};

struct Line::Impl {
  Impl(sim::Kernel& k, const LineParams& p, ContentionLog log)
      : failsafe(p.failsafe_level),
        // Idle: CLOCK driven HIGH by the master, DATA driven LOW by the encoder (docs/model.md §11).
        m_clock_out(k, "m_clock_out", true), m_data_out(k, "m_data_out", false),
        m_data_enable(k, "m_data_enable", false), m_data_in(k, "m_data_in", false),
        e_clock_in(k, "e_clock_in", true), e_data_out(k, "e_data_out", false),
        e_data_enable(k, "e_data_enable", true), e_data_in(k, "e_data_in", false),
        m_clock(k, "m_clock", true), e_clock(k, "e_clock", true),
        m_clock_line(k, "m_clock_line", true), e_clock_line(k, "e_clock_line", true),
        m_data_line(k, "m_data_line", false), e_data_line(k, "e_data_line", false),
        m_drive_level(k, "m_drive_level", false), m_drive_en(k, "m_drive_en", false),
        e_drive_level(k, "e_drive_level", false), e_drive_en(k, "e_drive_en", true),
        m_level_at_e(k, "m_level_at_e", false), m_en_at_e(k, "m_en_at_e", false),
        e_level_at_m(k, "e_level_at_m", false), e_en_at_m(k, "e_en_at_m", true),
        m_data(k, "m_data", false), e_data(k, "e_data", false),
        m_driven(k, "m_driven", true), e_driven(k, "e_driven", true),
        clock_driver(k, m_clock_out, m_clock_line, p.master.driver_delay),
        clock_cable(k, m_clock_line, e_clock_line, p.cable_delay()),
        clock_receiver(k, e_clock, e_clock_in, p.encoder.receiver_delay),
        m_level_driver(k, m_data_out, m_drive_level, p.master.driver_delay),
        m_en_driver(k, m_data_enable, m_drive_en, p.master.enable_delay, p.master.disable_delay),
        e_tap_level(k, "e_tap_level_0", false), e_tap_en(k, "e_tap_en_0", true),
        e_level_driver(k, e_data_out, e_tap_level, p.encoder.driver_delay),
        e_en_driver(k, e_data_enable, e_tap_en, p.encoder.enable_delay, p.encoder.disable_delay),
        bus(e_drive_en, e_drive_level, log),
        m_level_cable(k, m_drive_level, m_level_at_e, p.cable_delay()),
        m_en_cable(k, m_drive_en, m_en_at_e, p.cable_delay()),
        e_level_cable(k, e_drive_level, e_level_at_m, p.cable_delay()),
        e_en_cable(k, e_drive_en, e_en_at_m, p.cable_delay()),
        master_pin(ObservationPoint::MasterPins, m_drive_en, m_drive_level, e_en_at_m, e_level_at_m, m_data_line,
                   m_driven, log, failsafe),
        encoder_pin(ObservationPoint::EncoderPins, e_drive_en, e_drive_level, m_en_at_e, m_level_at_e,
                    e_data_line, e_driven, log, failsafe),
        m_clock_fault(k, m_clock_line, m_clock), e_clock_fault(k, e_clock_line, e_clock),
        m_data_fault(k, m_data_line, m_data), e_data_fault(k, e_data_line, e_data),
        m_receiver(k, m_data, m_data_in, p.master.receiver_delay),
        e_receiver(k, e_data, e_data_in, p.encoder.receiver_delay) {
    bus.add(e_tap_en, e_tap_level);
  }

  bool failsafe;
  Signal m_clock_out, m_data_out, m_data_enable, m_data_in;
  Signal e_clock_in, e_data_out, e_data_enable, e_data_in;
  Signal m_clock, e_clock;
  Signal m_clock_line, e_clock_line, m_data_line, e_data_line;  // before the pin faults
  Signal m_drive_level, m_drive_en, e_drive_level, e_drive_en;
  Signal m_level_at_e, m_en_at_e, e_level_at_m, e_en_at_m;
  Signal m_data, e_data;
  Signal m_driven, e_driven;
  TransportDelay clock_driver, clock_cable, clock_receiver;
  TransportDelay m_level_driver, m_en_driver;
  Signal e_tap_level, e_tap_en;
  TransportDelay e_level_driver, e_en_driver;
  EncoderBus bus;
  std::deque<EncoderTap> taps;
  TransportDelay m_level_cable, m_en_cable, e_level_cable, e_en_cable;
  PinResolver master_pin, encoder_pin;
  PinFault m_clock_fault, e_clock_fault, m_data_fault, e_data_fault;
  TransportDelay m_receiver, e_receiver;
};

Line::Line(sim::Kernel& kernel, const LineParams& params) : kernel_(kernel), params_(params) {
  params_.validate();
  cable_delay_ = params_.cable_delay();
  impl_ = std::make_unique<Impl>(kernel_, params_, ContentionLog(*this));
}

Line::~Line() = default;

void Line::on_contention(ContentionListener listener) { contention_listeners_.push_back(std::move(listener)); }

std::uint64_t Line::begin_contention(ObservationPoint where, bool between_encoders) {
  const Contention c{where, kernel_.now(), Time::max(), between_encoders, contentions_seen_++};
  if (contentions_.size() < contention_log_limit_) contentions_.push_back(c);
  open_contentions_.push_back(c);
  for (const auto& listener : contention_listeners_) listener(c);
  return c.sequence;
}

void Line::end_contention(std::uint64_t sequence) {
  const auto open = std::find_if(open_contentions_.begin(), open_contentions_.end(),
                                 [&](const Contention& c) { return c.sequence == sequence; });
  if (open == open_contentions_.end()) return;
  Contention c = *open;
  open_contentions_.erase(open);
  c.end = kernel_.now();
  // The log holds contentions in the order they began.
  const auto logged = std::lower_bound(contentions_.begin(), contentions_.end(), sequence,
                                       [](const Contention& l, std::uint64_t s) { return l.sequence < s; });
  if (logged != contentions_.end() && logged->sequence == sequence) logged->end = c.end;
  for (const auto& listener : contention_listeners_) listener(c);
}

Line::MasterSide Line::master() {
  return {impl_->m_clock_out, impl_->m_data_out, impl_->m_data_enable, impl_->m_data_in};
}

Line::EncoderSide Line::encoder() {
  return {impl_->e_clock_in, impl_->e_data_out, impl_->e_data_enable, impl_->e_data_in};
}

Line::EncoderSide Line::add_encoder() {
  auto& tap = impl_->taps.emplace_back(kernel_, params_, std::to_string(impl_->taps.size() + 1));
  impl_->bus.add(tap.en, tap.level);
  return {impl_->e_clock_in, tap.data_out, tap.data_enable, impl_->e_data_in};
}

Line::Pins Line::pins(ObservationPoint where) {
  if (where == ObservationPoint::MasterPins)
    return {impl_->m_clock, impl_->m_data, impl_->m_drive_en, impl_->m_driven};
  return {impl_->e_clock, impl_->e_data, impl_->e_drive_en, impl_->e_driven};
}

Time Line::pin_round_trip(Time encoder_output_delay) const {
  return 2 * cable_delay_ + params_.encoder.receiver_delay + encoder_output_delay +
         params_.encoder.driver_delay;
}

Time Line::round_trip(Time encoder_output_delay) const {
  return params_.master.driver_delay + pin_round_trip(encoder_output_delay) + params_.master.receiver_delay;
}

void Line::set_cable(double length_m, Time delay_per_m) {
  LineParams next = params_;
  next.cable_length_m = length_m;
  next.cable_delay_per_m = delay_per_m;
  next.validate();
  params_ = next;
  cable_delay_ = params_.cable_delay();
  const Time d = cable_delay_;
  for (TransportDelay* t : {&impl_->clock_cable, &impl_->m_level_cable, &impl_->m_en_cable, &impl_->e_level_cable,
                            &impl_->e_en_cable})
    t->set_delays(d, d);
}

PinFault& Line::fault(Wire wire, ObservationPoint end) {
  const bool master = end == ObservationPoint::MasterPins;
  if (wire == Wire::Clock) return master ? impl_->m_clock_fault : impl_->e_clock_fault;
  return master ? impl_->m_data_fault : impl_->e_data_fault;
}

void Line::invert(Wire wire, ObservationPoint end, Time width) {
  if (width <= Time::zero()) throw std::invalid_argument("a glitch must be longer than 0, got " + sim::format_time(width));
  fault(wire, end).invert_for(width);
}

void Line::stick(Wire wire, ObservationPoint end, std::optional<bool> level) { fault(wire, end).stick(level); }

void Line::set_driver_disable_delay(ObservationPoint end, Time delay) {
  if (delay < Time::zero() || delay > kMaxLateRelease)
    throw std::invalid_argument("driver disable delay must be 0 .. " + sim::format_time(kMaxLateRelease) + ", got " +
                                sim::format_time(delay));
  // A fault, not a configuration: params() keep the transceiver as configured.
  if (end == ObservationPoint::MasterPins) impl_->m_en_driver.set_delays(params_.master.enable_delay, delay);
  else impl_->e_en_driver.set_delays(params_.encoder.enable_delay, delay);
}

void Line::set_failsafe_level(bool level) {
  params_.failsafe_level = level;
  impl_->failsafe = level;
  impl_->master_pin.resolve();
  impl_->encoder_pin.resolve();
}

}  // namespace endatsim::line

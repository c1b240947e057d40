#include "endatsim/cosim/bench.hpp"

#include <algorithm>
#include <utility>

#include "endatsim/line/line.hpp"
#include "endatsim/scenarios/capture_check.hpp"
#include "endatsim/scenarios/declarations.hpp"
#include "endatsim/scenarios/events.hpp"
#include "endatsim/scenarios/interrupt.hpp"
#include "endatsim/scenarios/waveform_names.hpp"
#include "endatsim/sim/vcd.hpp"
#include "endatsim/slave/encoder.hpp"

namespace endatsim::cosim {
namespace {

constexpr std::uint64_t kWatchEvery = 4096;  // kernel events between looks at the limits

// The encoder's delay from CLOCK to DATA at its own connector: receiver, logic and driver.
Time clock_to_data_at_encoder(const scenarios::Scenario& s) {
  return s.line.encoder.receiver_delay + s.encoder.output_delay + s.line.encoder.driver_delay;
}

checker::DecoderParams decoder_params(const scenarios::Scenario& s, Time clock_to_data) {
  return {.position_bits = s.encoder.position_bits,
          .clock_to_data = clock_to_data,
          .t_m = s.encoder.t_m,
          .supplement_ignore_clocks = s.encoder.supplement_ignore_clocks};
}

}  // namespace

// Everything the bench owns, in construction order: the line before what listens to it.
struct Bench::Parts {
  Parts(const scenarios::Scenario& s, std::uint64_t seed)
      : line(kernel, s.line),
        encoder(kernel, line, s.encoder),
        checker(kernel, line, scenarios::declared_encoder(s.encoder), {}, s.checker),
        // A bench's bit flips carry their own width (the loader insists), so no clock period is needed.
        events(kernel, line, encoder, nullptr, checker, s.events, seed, Time::zero()),
        at_encoder(decoder_params(s, clock_to_data_at_encoder(s))),
        at_master(decoder_params(s, line.pin_round_trip(s.encoder.output_delay))) {
    for (const auto& p : s.bus) bus.push_back(std::make_unique<slave::Encoder>(kernel, line.add_encoder(), p));
  }
  sim::Kernel kernel;
  line::Line line;
  slave::Encoder encoder;
  std::vector<std::unique_ptr<slave::Encoder>> bus;
  checker::TimingChecker checker;
  scenarios::EventDriver events;
  checker::FrameDecoder at_encoder;  // the transaction log, as a logic analyzer at the encoder would read it
  checker::FrameDecoder at_master;   // where the master's frames begin: frame-indexed events
  std::uint64_t master_frames = 0;
  std::unique_ptr<sim::VcdWriter> vcd;
};

Bench::Bench(const scenarios::Scenario& bench, BenchOptions options)
    : bench_(bench), options_(std::move(options)),
      parts_(std::make_unique<Parts>(bench, options_.seed.value_or(bench.seed))),
      limits_(scenarios::resolve_limits(bench, options_.limits)),
      max_time_(limits_.max_time ? std::min(*limits_.max_time, bench.max_time) : bench.max_time) {
  auto& p = *parts_;
  p.kernel.watch(std::min<std::uint64_t>(kWatchEvery, limits_.kernel_events), sim::bind<&Bench::check_limits>(this));
  p.line.master().data_in.on_change(sim::bind<&Bench::on_data_in_change>(this));
  const auto master_pins = p.line.pins(line::ObservationPoint::MasterPins);
  master_pins.clock.on_change(sim::bind<&Bench::on_master_clock>(this));
  master_pins.data.on_change(sim::bind<&Bench::on_master_data>(this));
  const auto encoder_pins = p.line.pins(line::ObservationPoint::EncoderPins);
  encoder_pins.clock.on_change(sim::bind<&Bench::on_encoder_clock>(this));
  encoder_pins.data.on_change(sim::bind<&Bench::on_encoder_data>(this));
  if (options_.vcd_path) {
    p.vcd = std::make_unique<sim::VcdWriter>(p.kernel, *options_.vcd_path);
    scenarios::add_pin_waves(*p.vcd, p.line);
    p.vcd->start();
  }
}

Bench::~Bench() = default;

Time Bench::now() const { return parts_->kernel.now(); }

void Bench::advance_to(Time t) {
  if (should_stop()) return;
  parts_->kernel.advance_to(t);
}

void Bench::drive(MasterPin pin, bool level) {
  if (should_stop()) return;
  auto m = parts_->line.master();
  switch (pin) {
    case MasterPin::Clock: m.clock_out.write(level); break;
    case MasterPin::DataOut: m.data_out.write(level); break;
    case MasterPin::DataEnable: m.data_enable.write(level); break;
  }
  parts_->kernel.advance_to(parts_->kernel.now());  // commit the write and run its listeners now
}

std::optional<Time> Bench::next_event_time() const {
  if (!incomplete_.empty()) return std::nullopt;  // a bench that stopped wakes no one again
  return parts_->kernel.next_event_time();
}

bool Bench::data_in() const { return parts_->line.master().data_in.read(); }

void Bench::on_data_in(std::function<void(Time, bool)> callback) { data_in_callback_ = std::move(callback); }

void Bench::on_data_in_change(std::uint64_t level) {
  if (data_in_callback_) data_in_callback_(now(), level != 0);
}

void Bench::on_master_clock(std::uint64_t level) {
  if (parts_->at_master.on_clock(now(), level != 0)) parts_->events.frame_started(parts_->master_frames++);
  parts_->at_master.take_finished();  // only the frames' beginnings matter here
}

void Bench::on_master_data(std::uint64_t level) { parts_->at_master.on_data(now(), level != 0); }

void Bench::on_encoder_clock(std::uint64_t level) {
  parts_->at_encoder.on_clock(now(), level != 0);
  drain_frames();
}

void Bench::on_encoder_data(std::uint64_t level) {
  parts_->at_encoder.on_data(now(), level != 0);
  drain_frames();
}

void Bench::drain_frames() {
  for (auto& f : parts_->at_encoder.take_finished()) {
    ++frames_decoded_;
    const bool clean = f.clean();
    if (clean) ++frames_clean_;
    if (clean && f.command && protocol::info(*f.command).answer == protocol::AnswerFormat::Parameter)
      last_parameter_on_wires_ = static_cast<std::uint16_t>(f.fields[static_cast<std::size_t>(protocol::Field::Parameter)]);
    if (options_.on_frame) options_.on_frame(f);
    if (frames_.size() < scenarios::kMaxFramesKept) frames_.push_back(std::move(f));
  }
}

void Bench::report_position(std::uint64_t position) {
  // The encoder latched the position at FE1 of the last frame that answers with one (2.3.1).
  const auto& frames = parts_->encoder.frames();
  const auto it = std::find_if(frames.rbegin(), frames.rend(), [](const slave::EncoderFrame& f) {
    return f.command && protocol::info(*f.command).answer == protocol::AnswerFormat::Position;
  });
  Reported r{now(), position, std::nullopt};
  if (it != frames.rend()) r.truth = it->position;
  positions_.push_back(r);
  check_limits();
}

void Bench::report_parameter(std::uint16_t parameter) {
  // The parameter of an answer is the last one the wires carried; a master reports it as the
  // frame ends, and the decoder closes a frame at the next FE1, so look at the frame in progress too.
  drain_frames();
  std::optional<std::uint64_t> truth = last_parameter_on_wires_;
  if (const auto* f = parts_->at_encoder.current();
      f != nullptr && f->clean() && f->command &&
      protocol::info(*f->command).answer == protocol::AnswerFormat::Parameter)
    truth = f->fields[static_cast<std::size_t>(protocol::Field::Parameter)];
  parameters_.push_back({now(), parameter, truth});
  check_limits();
}

void Bench::note(std::string text) {
  if (std::find(notes_.begin(), notes_.end(), text) == notes_.end()) notes_.push_back(std::move(text));
}

void Bench::unknown_level(std::string text) {
  ++unknown_levels_;
  note(std::move(text));
}

bool Bench::should_stop() {
  if (incomplete_.empty() && scenarios::interrupt_signal() != 0) check_limits();
  return !incomplete_.empty() || now() >= max_time_;
}

// Called every few thousand kernel events and as records are added.
void Bench::check_limits() {
  if (!incomplete_.empty()) return;
  using namespace scenarios;
  if (const int signal = interrupt_signal(); signal != 0) {
    end_early("interrupted by " + signal_name(signal), signal);
  } else if (parts_->kernel.events_processed() >= limits_.kernel_events) {
    end_early("limit kernel_events reached: " + std::to_string(parts_->kernel.events_processed()) +
              " kernel events, at most " + std::to_string(limits_.kernel_events) + " (" + kKernelEventsOption +
              " or limits.kernel_events changes it)");
  } else if (const std::uint64_t n = records(); n >= limits_.records) {
    end_early("limit records reached: " + std::to_string(n) + " positions, parameters, frames and violations kept, at most " +
              std::to_string(limits_.records) + " (" + kRecordsOption + " or limits.records changes it)");
  }
}

void Bench::end_early(const std::string& why, int signal) {
  incomplete_ = why + "; the run ended at " + sim::format_time(now());
  interrupted_ = signal;
  parts_->kernel.stop();
}

bool Bench::cut_by_time_limit(Time end) const { return max_time_ < bench_.max_time && end >= max_time_; }

std::uint64_t Bench::records() const {
  std::uint64_t n = positions_.size() + parameters_.size() + parts_->encoder.frames().size() +
                    parts_->checker.violations().size();
  for (const auto& e : parts_->bus) n += e->frames().size();
  return n;
}

bool BenchResult::passed() const {
  return std::all_of(expectations.begin(), expectations.end(), [](const auto& e) { return e.passed; });
}

namespace {

std::string compare_line(const Reported& r) {
  return "at " + sim::format_time(r.at) + " the master reported " + std::to_string(r.value) + ", " +
         (r.truth ? "the encoder's was " + std::to_string(*r.truth) : std::string("nothing to compare with yet"));
}

scenarios::ExpectationResult all_match(const std::string& name, const std::vector<Reported>& reported,
                                       const std::string& what) {
  const auto bad = std::find_if(reported.begin(), reported.end(), [](const Reported& r) { return !r.matches(); });
  if (reported.empty()) return {name, false, "the master reported no " + what};
  if (bad != reported.end())
    return {name, false, "#" + std::to_string(bad - reported.begin()) + ": " + compare_line(*bad)};
  return {name, true, std::to_string(reported.size()) + " " + what + "(s) as sent"};
}

}  // namespace

void Bench::judge(BenchResult& r) const {
  const auto& e = bench_.expect;
  // A master that never let the simulation end (hung polling, a testbench that never stops) did
  // not do what it was meant to.
  if (!incomplete_.empty()) r.expectations.push_back({"complete", false, incomplete_});
  // A run that the max_time limit cut short is incomplete, as `endatsim run --max-time` says, not
  // a master that ran past the bench's own max_time.
  if (!cut_by_time_limit(r.simulated))
    r.expectations.push_back({"ended before max_time", r.simulated < max_time_,
                              r.simulated < max_time_ ? "at " + sim::format_time(r.simulated)
                                                      : "still running at the bench's max_time " + sim::format_time(max_time_)});
  // As `endatsim check` refuses a capture in which no frame began: nothing was judged.
  if (r.frames_decoded == 0) r.expectations.push_back({"frames", false, "no frame began at the encoder's connector: nothing was judged"});
  r.expectations.push_back({"pins at known levels", unknown_levels_ == 0,
                            unknown_levels_ == 0 ? "CLOCK and DATA's driver at 0 or 1 throughout"
                                                 : std::to_string(unknown_levels_) + " time(s) unknown (see the notes)"});
  if (e.positions_match_encoder.value_or(false)) {
    auto x = all_match("positions_match_encoder", r.positions, "position");
    if (!x.passed || r.positions.empty()) r.expectations.push_back(std::move(x));
    else r.expectations.push_back({x.name, true, std::to_string(r.positions.size()) + " positions equal the latched ones"});
  }
  if (e.positions) {
    std::vector<std::uint64_t> read;
    for (const auto& p : r.positions) read.push_back(p.value);
    const bool ok = read == *e.positions;
    std::string detail = ok ? "all " + std::to_string(read.size()) + " as expected" : "reported";
    if (!ok)
      for (std::size_t i = 0; i < read.size() && i < 8; ++i) detail += " " + std::to_string(read[i]);
    r.expectations.push_back({"positions", ok, detail});
  }
  // A master that reports a parameter it did not receive decodes wrongly, asked or not.
  if (!r.parameters.empty()) r.expectations.push_back(all_match("parameters_match_wires", r.parameters, "parameter"));
  scenarios::judge_violations(e, r.violations, r.expectations);
}

BenchResult Bench::finish() {
  if (finished_) throw std::logic_error("Bench::finish called twice");
  finished_ = true;
  should_stop();  // a signal that came while the outside simulator was ending it
  auto& p = *parts_;
  // The outside simulator ends the run where it likes, as a capture's end: a frame it cuts is not
  // judged for its clock pulses.
  p.checker.end_run_early(p.kernel.now());
  if (incomplete_.empty() && cut_by_time_limit(p.kernel.now()))
    end_early("limit max_time reached: " + sim::format_time(max_time_) + " simulated, less than the bench's " +
              sim::format_time(bench_.max_time) + " (" + scenarios::kMaxTimeOption + " changes it)");
  p.checker.finish();
  p.at_encoder.finish();
  drain_frames();
  if (p.vcd) p.vcd->finish();
  BenchResult r;
  r.file = bench_.file;
  r.name = bench_.name;
  r.description = bench_.description;
  r.seed = options_.seed.value_or(bench_.seed);
  r.simulated = p.kernel.now();
  r.events = p.kernel.events_processed();
  r.frames_decoded = frames_decoded_;
  r.frames_clean = frames_clean_;
  r.frames = std::move(frames_);
  r.positions = positions_;
  r.parameters = parameters_;
  r.violations = p.checker.violations();
  r.conformance = p.checker.conformance();
  r.conclusion = p.checker.conclusion();
  r.notes = notes_;
  r.events_not_acted = p.events.not_acted();
  r.frame_cut_by_end = p.checker.frame_cut_by_end();
  const sim::Signal& clock = p.line.pins(line::ObservationPoint::EncoderPins).clock;
  r.clock_at_end = clock.read();
  r.clock_last_change = clock.last_change();
  r.incomplete = incomplete_;
  r.interrupted = interrupted_;
  judge(r);
  return r;
}

}  // namespace endatsim::cosim

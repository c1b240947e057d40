#include "endatsim/scenarios/runner.hpp"

#include "endatsim/scenarios/declarations.hpp"

#include "endatsim/scenarios/events.hpp"
#include "endatsim/scenarios/interrupt.hpp"
#include "endatsim/scenarios/transaction_log.hpp"
#include "endatsim/scenarios/waveform_names.hpp"

#include <algorithm>
#include <memory>
#include <unordered_map>

#include "endatsim/master/functions.hpp"
#include "endatsim/sim/vcd.hpp"
#include "endatsim/sim/text.hpp"

namespace endatsim::scenarios {
namespace {

std::uint64_t count_outcome(const ScenarioResult& r, std::string_view name) {
  for (const master::FrameOutcome o : master::kFrameOutcomes)
    if (master::to_string(o) == name) return r.tally.outcome(o);
  return 0;
}

}  // namespace

PositionComparison compare_positions_with_encoder(const Scenario& s, const ScenarioResult& r) {
  const std::vector<Time> paths = clock_paths(s);
  PositionComparator comparator;
  for (const auto& f : r.frames) {
    if (f.measurement || f.outcome != master::FrameOutcome::Ok ||
        protocol::info(f.command).answer != protocol::AnswerFormat::Position)
      continue;
    // The encoder frames up to this one's start: encoder_frame_of looks back from the newest.
    const auto upto = std::upper_bound(r.encoder_frames.begin(), r.encoder_frames.end(), f.start + *std::max_element(paths.begin(), paths.end()),
                                       [](Time t, const slave::EncoderFrame& ef) { return t < ef.start; });
    comparator.add(f, encoder_frame_of(f, paths, std::span(r.encoder_frames.begin(), upto)));
  }
  return {comparator.match(), comparator.detail()};
}

namespace {

void judge_positions(const Scenario& s, ScenarioResult& r) {
  const auto& e = s.expect;
  if (e.positions_match_encoder.value_or(false) && r.positions_match)
    r.expectations.push_back({"positions_match_encoder", r.positions_match->match, r.positions_match->detail});
  if (e.positions) {
    const auto& read = r.positions_read;  // as many as expected and one more, if there were
    const bool ok = read == *e.positions;
    std::string detail = ok ? "all " + std::to_string(read.size()) + " as expected" : "read";
    if (!ok)
      for (std::size_t i = 0; i < read.size() && i < 8; ++i) detail += " " + std::to_string(read[i]);
    r.expectations.push_back({"positions", ok, detail});
  }
}

void judge_delay(const Scenario& s, ScenarioResult& r) {
  if (!s.expect.delay_measurement) return;
  const auto& d = *s.expect.delay_measurement;
  const master::DelayMeasurementResult* last = r.last_measurement ? &*r.last_measurement : nullptr;
  if (d.accepted) {
    const bool got = last != nullptr && last->accepted;
    r.expectations.push_back({"delay_measurement.accepted", got == *d.accepted,
                              last == nullptr ? "no measurement ran"
                                              : (last->accepted ? "accepted" : "rejected: " + last->reason)});
  }
  if (d.max_error || d.max_error_is_eighth) {
    const Time limit = d.max_error_is_eighth ? sim::period_of(s.master.f_c) / protocol::limit::kMeasurementSpreadPeriodDivisor
                                              : *d.max_error;
    if (last == nullptr || !last->accepted) {
      r.expectations.push_back({"delay_measurement.max_error", false, "no accepted measurement"});
      return;
    }
    const Time error = last->t_d > r.true_round_trip ? last->t_d - r.true_round_trip : r.true_round_trip - last->t_d;
    r.expectations.push_back({"delay_measurement.max_error", error <= limit,
                              "measured " + sim::format_time(last->t_d) + ", true round trip " +
                                  sim::format_time(r.true_round_trip) + ", error " + sim::format_time(error) +
                                  " (limit " + sim::format_time(limit) + ")"});
  }
}

using sim::hex_0x;

// One operation's "expect", against the last frame the operation sent.
void judge_operation(std::size_t index, const FrameExpectation& e, ScenarioResult& r) {
  const auto it = r.operation_frames.find(index);
  const master::FrameResult* f = it == r.operation_frames.end() ? nullptr : &it->second;
  const std::string name = "script/" + std::to_string(index) + "/expect";
  if (f == nullptr) {
    r.expectations.push_back({name, false, "the operation sent no frame"});
    return;
  }
  std::vector<std::string> wrong;
  const auto differ = [&](const std::string& what, const std::string& got, const std::string& want) {
    if (got != want) wrong.push_back(what + " " + got + " (expected " + want + ")");
  };
  if (e.outcome) differ("outcome", std::string(master::to_string(f->outcome)), *e.outcome);
  if (e.position) differ("position", std::to_string(f->position), std::to_string(*e.position));
  if (e.error1) differ("F1", std::to_string(f->error1), std::to_string(*e.error1));
  if (e.echo_address) differ("echo address", hex_0x(f->echo_address, 2), hex_0x(*e.echo_address, 2));
  if (e.echo_parameter) differ("echo parameter", hex_0x(f->echo_parameter, 4), hex_0x(*e.echo_parameter, 4));
  if (e.test_value) differ("test value", hex_0x(f->test_value, 10), hex_0x(*e.test_value, 10));
  if (e.additional_data) {
    differ("additional data count", std::to_string(f->additional_data.size()), std::to_string(e.additional_data->size()));
    for (std::size_t i = 0; i < e.additional_data->size() && i < f->additional_data.size(); ++i) {
      const auto& want = (*e.additional_data)[i];
      const auto& got = f->additional_data[i];
      const std::string at = "additional data " + std::to_string(i) + " ";
      differ(at + "information", std::string(protocol::info(got.information()).key),
             std::string(protocol::info(want.information).key));
      if (want.data) differ(at + "data", hex_0x(got.data, 4), hex_0x(*want.data, 4));
      if (want.busy) differ(at + "busy", std::to_string(got.busy()), std::to_string(*want.busy));
      if (want.rm)
        differ(at + "RM", std::to_string((got.status & protocol::AdditionalDataStatus::kReferenceMark) != 0),
               std::to_string(*want.rm));
    }
  }
  std::string detail = "frame " + std::to_string(f->index);
  for (const auto& w : wrong) detail += "; " + w;
  r.expectations.push_back({name, wrong.empty(), detail});
}

void judge_memory(const Scenario& s, ScenarioResult& r) {
  for (const auto& m : s.expect.memory) {
    std::string name = "memory." + std::string(protocol::info(m.area).key) + "/" + hex_0x(m.address, 2);
    if (m.encoder > 0) name = "bus/" + std::to_string(m.encoder - 1) + "/" + name;
    if (m.encoder > r.bus_memory.size()) {
      r.expectations.push_back({name, false, "there is no such encoder on the bus"});
      continue;
    }
    const slave::MemoryImage& image = m.encoder == 0 ? r.encoder_memory : r.bus_memory[m.encoder - 1];
    const auto& areas = image.areas;
    const std::vector<std::uint16_t>* words = nullptr;
    if (m.area == protocol::MemoryArea::Section2) {
      if (m.block < image.section2_blocks.size()) words = &image.section2_blocks[m.block];
    } else if (const auto it = areas.find(m.area); it != areas.end()) {
      words = &it->second;
    }
    if (words == nullptr || m.address >= words->size()) {
      r.expectations.push_back({name, false, "the encoder has no such word"});
      continue;
    }
    const std::uint16_t v = (*words)[m.address];
    r.expectations.push_back({name, v == m.value, hex_0x(v, 4) + " (expected " + hex_0x(m.value, 4) + ")"});
  }
}

void judge_startup(const StartupExpectation& e, ScenarioResult& r) {
  const auto& got = r.startup;
  if (e.completed)
    r.expectations.push_back({"startup.completed", got.completed == *e.completed,
                              got.completed ? "every frame answered" : std::to_string(got.failed_frames) + " frames failed"});
  const auto word = [&](const char* name, const std::optional<std::uint16_t>& want,
                        const std::optional<std::uint16_t>& read) {
    if (!want) return;
    r.expectations.push_back({std::string("startup.") + name, read == want,
                              (read ? hex_0x(*read, 4) : std::string("not read")) + " (expected " + hex_0x(*want, 4) + ")"});
  };
  word("errors", e.errors, got.errors);
  word("warnings", e.warnings, got.warnings);
  word("word13", e.word13, got.word13);
  word("word37", e.word37, got.word37);
}

// Counts per kind (safety findings by function, diagnosis notes by kind) against their
// expectations; a kind not listed must not occur. Each result quotes the first message.
template <class Kind, std::size_t N, class Item>
void judge_kinds(const std::string& prefix, const std::array<Kind, N>& kinds, const std::map<std::string, CountMatcher>& expected,
                 const std::vector<Item>& items, Kind Item::*kind_of, ScenarioResult& r) {
  for (const Kind k : kinds) {
    const std::string name(master::to_string(k));
    const auto n = static_cast<std::uint64_t>(std::count_if(items.begin(), items.end(), [&](const Item& x) { return x.*kind_of == k; }));
    const auto first = std::find_if(items.begin(), items.end(), [&](const Item& x) { return x.*kind_of == k; });
    const std::string quote = first == items.end() ? "" : ": " + first->message;
    const auto it = expected.find(name);
    if (it != expected.end())
      r.expectations.push_back({prefix + name, it->second.matches(n), std::to_string(n) + " (expected " + it->second.text + ")" + quote});
    else if (n != 0)
      r.expectations.push_back({prefix + name, false, std::to_string(n) + " (expected none: not listed)" + quote});
  }
}

void judge_safety(const SafetyExpectation& e, ScenarioResult& r) {
  const auto& got = r.safety;
  judge_kinds("safety.findings.", master::kSafetyFunctions, e.findings, got.findings, &master::SafetyFinding::function, r);
  if (e.axis_released)
    r.expectations.push_back({"safety.axis_released", got.axis_released == *e.axis_released,
                              got.axis_released ? "released at " + sim::format_time(got.released_at) + " with position " +
                                                      std::to_string(got.release_position)
                                                : "not released"});
  if (e.release_position_correct)
    r.expectations.push_back({"safety.release_position_correct",
                              r.release_position_correct == e.release_position_correct,
                              !r.release_position_correct ? "no released position"
                              : *r.release_position_correct ? "the encoder measured " + std::to_string(got.release_position)
                                                            : "released " + std::to_string(got.release_position) +
                                                                  ", not what the encoder measured"});
  if (e.undetected_errors)
    r.expectations.push_back({"safety.undetected_errors", e.undetected_errors->matches(r.undetected_errors),
                              std::to_string(r.undetected_errors) + " (expected " + e.undetected_errors->text + ")"});
  if (e.position_comparisons)
    r.expectations.push_back({"safety.position_comparisons", e.position_comparisons->matches(got.position_comparisons),
                              std::to_string(got.position_comparisons) + " (expected " + e.position_comparisons->text + ")"});
}

void judge_diagnosis(const DiagnosisExpectation& e, ScenarioResult& r) {
  namespace dg = protocol::diagnosis;
  if (!r.diagnosis) {
    r.expectations.push_back({"diagnosis", false, "the master's diagnostics are not enabled (master.diagnostics.enabled)"});
    return;
  }
  const auto& got = *r.diagnosis;
  judge_kinds("diagnosis.notes.", master::kDiagnosisNoteKinds, e.notes, got.notes, &master::DiagnosisNote::kind, r);
  const auto reading = [&](const std::string& what, const master::DiagnosisReading* got_reading, unsigned want, bool temperature) {
    const auto show = [temperature](unsigned v) { return temperature ? dg::temperature_string(v) : std::to_string(v); };
    r.expectations.push_back({"diagnosis." + what, got_reading != nullptr && got_reading->last == want,
                              got_reading == nullptr ? "never read (expected " + show(want) + ")"
                                                     : show(got_reading->last) + " (expected " + show(want) + ")"});
  };
  for (const auto& [address, want] : e.valuation_numbers) {
    const auto it = got.valuation_numbers.find(address);
    reading("valuation_numbers." + std::to_string(address), it == got.valuation_numbers.end() ? nullptr : &it->second, want, false);
  }
  if (e.temperature1) reading("temperature_1", got.temperature1 ? &*got.temperature1 : nullptr, *e.temperature1, true);
  if (e.temperature2) reading("temperature_2", got.temperature2 ? &*got.temperature2 : nullptr, *e.temperature2, true);
  for (const auto& [address, want] : e.additional_sensors) {
    const auto it = got.additional_sensors.find(address);
    reading("additional_sensors." + std::to_string(address), it == got.additional_sensors.end() ? nullptr : &it->second, want, true);
  }
  const auto word = [&](const std::string& what, const std::optional<std::uint16_t>& want, const std::optional<std::uint16_t>& have) {
    if (want)
      r.expectations.push_back({"diagnosis." + what, have == want,
                                have ? std::to_string(*have) + " (expected " + std::to_string(*want) + ")" : "never read"});
  };
  word("configuration", e.configuration, got.configuration);
  word("warnings", e.warnings, got.warnings);
  if (e.ignored_addresses)
    r.expectations.push_back({"diagnosis.ignored_addresses", e.ignored_addresses->matches(got.ignored_addresses),
                              std::to_string(got.ignored_addresses) + " (expected " + e.ignored_addresses->text + ")"});
}

void judge(const Scenario& s, ScenarioResult& r) {
  if (!r.incomplete.empty()) r.expectations.push_back({"complete", false, r.incomplete});
  r.expectations.push_back({"script finished", r.finished,
                            r.finished             ? "at " + sim::format_time(r.simulated)
                            : r.incomplete.empty() ? "still running at max_time " + sim::format_time(s.max_time)
                                                   : "the run ended early at " + sim::format_time(r.simulated)});
  for (const auto& [name, m] : s.expect.outcomes) {
    const auto n = count_outcome(r, name);
    r.expectations.push_back({"outcomes." + name, m.matches(n), std::to_string(n) + " (expected " + m.text + ")"});
  }
  judge_positions(s, r);
  judge_delay(s, r);
  judge_violations(s.expect, finding_counts(r.conformance), r.expectations);
  for (std::size_t i = 0; i < s.operation_expectations.size(); ++i)
    if (s.operation_expectations[i]) judge_operation(i, *s.operation_expectations[i], r);
  judge_memory(s, r);
  if (s.expect.startup) judge_startup(*s.expect.startup, r);
  if (s.expect.safety) judge_safety(*s.expect.safety, r);
  if (s.expect.diagnosis) judge_diagnosis(*s.expect.diagnosis, r);
  if (s.expect.checksum_ok) {
    const bool got = r.checksum && r.checksum->ok();
    r.expectations.push_back({"checksum", r.checksum.has_value() && got == *s.expect.checksum_ok,
                              !r.checksum ? "no verify_checksum ran"
                              : !r.checksum->complete ? "not every word was read"
                                                      : (got ? "ok" : "mismatch") + std::string(": word 47 ") +
                                                            std::to_string(r.checksum->stored) + ", sum " +
                                                            std::to_string(r.checksum->computed)});
  }
  for (const auto& [name, want, got] : {std::tuple{"retries", &s.expect.retries, r.retries},
                                        {"remeasurements", &s.expect.remeasurements, r.remeasurements}})
    if (*want) r.expectations.push_back({name, (*want)->matches(got), std::to_string(got) + " (expected " + (*want)->text + ")"});
  if (s.expect.busy_timeouts)
    r.expectations.push_back({"busy_timeouts", s.expect.busy_timeouts->matches(r.busy_timeouts),
                              std::to_string(r.busy_timeouts) + " (expected " + s.expect.busy_timeouts->text + ")"});
  if (s.expect.max_busy_timeouts)
    r.expectations.push_back({"max_busy_timeouts", r.busy_timeouts <= *s.expect.max_busy_timeouts,
                              std::to_string(r.busy_timeouts)});
  if (s.expect.max_cycle_overruns) {
    r.expectations.push_back({"max_cycle_overruns", r.cycle_overruns <= *s.expect.max_cycle_overruns,
                              std::to_string(r.cycle_overruns)});
  }
}

// The decoded frames as a text trace of the VCD: the mode command from FE1 on, what came back
// from the frame's end on.
class DecodedTrace final : public master::MasterObserver {
 public:
  explicit DecodedTrace(sim::VcdWriter& vcd) : vcd_(vcd), trace_(vcd.add_text(std::string(kWaveformScope), "decoded")) {}
  void on_frame_start(const master::FrameResult& frame) override {
    vcd_.set_text(trace_, "#" + std::to_string(frame.index) + " " + std::string(protocol::info(frame.command).key));
  }
  void on_sample(const master::FrameResult&, unsigned, bool, bool) override {}
  bool wants_samples() const override { return false; }
  void on_frame_end(const master::FrameResult& frame) override {
    std::string line = transaction_line(transaction_tokens(frame, {}));
    line.erase(0, line.find('#'));  // the time is the trace's own
    vcd_.set_text(trace_, line);
  }

 private:
  sim::VcdWriter& vcd_;
  std::size_t trace_;
};

// Looks at the run every few thousand kernel events: an interruption, or a limit reached, stops
// the kernel at that event boundary.
class Watch {
 public:
  static constexpr std::uint64_t kEvery = 4096;
  Watch(sim::Kernel& kernel, const master::Master& master, const slave::Encoder& encoder,
        const std::vector<std::unique_ptr<slave::Encoder>>& bus, const checker::TimingChecker& checker, const Limits& limits)
      : kernel_(kernel), master_(master), encoder_(encoder), bus_(bus), checker_(checker), limits_(limits) {}
  void check() {
    if (progress != nullptr) {
      progress->simulated_ps.store(kernel_.now().count(), std::memory_order_relaxed);
      progress->frames.store(master_.frame_count(), std::memory_order_relaxed);
    }
    if (const int signal = interrupt_signal(); signal != 0) {
      interrupted = signal;
      end("interrupted by " + signal_name(signal));
    } else if (kernel_.events_processed() >= limits_.kernel_events) {
      end("limit kernel_events reached: " + std::to_string(kernel_.events_processed()) + " kernel events, at most " +
          std::to_string(limits_.kernel_events) + " (" + kKernelEventsOption + " or limits.kernel_events changes it)");
    } else if (const std::uint64_t n = records(); n >= limits_.records) {
      end("limit records reached: " + std::to_string(n) + " frames, measurements and violations kept, at most " +
          std::to_string(limits_.records) + " (" + kRecordsOption + " or limits.records changes it)");
    }
  }
  std::string reason;
  int interrupted = 0;
  RunProgress* progress = nullptr;  // kept up to date, when set

  std::uint64_t records() const {
    std::uint64_t n = master_.frames().size() + master_.measurements().size() + encoder_.frames().size() +
                      checker_.violations().size();
    for (const auto& e : bus_) n += e->frames().size();
    return n;
  }
  void end(const std::string& why) {
    reason = why + "; the run ended at " + sim::format_time(kernel_.now());
    kernel_.stop();
  }
  sim::Kernel& kernel_;
  const master::Master& master_;
  const slave::Encoder& encoder_;
  const std::vector<std::unique_ptr<slave::Encoder>>& bus_;
  const checker::TimingChecker& checker_;
  const Limits& limits_;
};

// A played frame runs no event at which the watch could stop the run: it is played only when no
// limit can be reached inside it.
class LimitRoom final : public FrameReplay::Room {
 public:
  // Beyond what the recorded frame added: a checker shown the frame may find more than it did.
  static constexpr std::uint64_t kRecordsSlack = 64;
  LimitRoom(const sim::Kernel& kernel, const Watch& watch, const Limits& limits) : kernel_(kernel), watch_(watch), limits_(limits) {}
  bool for_frame(std::uint64_t events, std::uint64_t records) const override {
    return kernel_.events_processed() + events < limits_.kernel_events &&
           watch_.records() + records + kRecordsSlack < limits_.records;
  }

 private:
  const sim::Kernel& kernel_;
  const Watch& watch_;
  const Limits& limits_;
};

}  // namespace

void judge_violations(const Expectations& expect, const std::vector<checker::Violation>& violations,
                      std::vector<ExpectationResult>& out) {
  std::map<std::string, std::uint64_t> counts;
  for (const auto& v : violations) ++counts[v.check];
  judge_violations(expect, counts, out);
}

std::map<std::string, std::uint64_t> finding_counts(const std::vector<checker::RowConformance>& rows) {
  std::map<std::string, std::uint64_t> counts;
  for (const auto& row : rows)
    if (const std::uint64_t n = row.violations + row.warnings + row.undecided; n != 0) counts[row.check] = n;
  return counts;
}

void judge_violations(const Expectations& expect, std::map<std::string, std::uint64_t> counts,
                      std::vector<ExpectationResult>& out) {
  for (const auto& [name, m] : expect.violations) {
    if (name == kAnyOtherCheck) continue;  // judged below
    const auto n = counts[name];
    out.push_back({"violations." + name, m.matches(n), std::to_string(n) + " (expected " + m.text + ")"});
  }
  const auto others = expect.violations.find(std::string(kAnyOtherCheck));
  if (others == expect.violations.end()) {
    for (const auto& [name, n] : counts) {
      if (expect.violations.count(name) != 0 || n == 0) continue;
      out.push_back({"violations." + name, false, std::to_string(n) + " (expected none: not listed)"});
    }
    return;
  }
  // "*": the findings of every check not named, counted together.
  std::uint64_t total = 0;
  std::string which;
  for (const auto& [name, n] : counts) {
    if (expect.violations.count(name) != 0 || n == 0) continue;
    total += n;
    which += (which.empty() ? ": " : ", ") + name + " " + std::to_string(n);
  }
  out.push_back({"violations." + std::string(kAnyOtherCheck), others->second.matches(total),
                 std::to_string(total) + " of checks not named (expected " + others->second.text + ")" + which});
}

bool ScenarioResult::passed() const {
  return std::all_of(expectations.begin(), expectations.end(), [](const auto& e) { return e.passed; });
}

ScenarioResult run_scenario(const Scenario& scenario, const RunOptions& options) {
  const Limits limits = resolve_limits(scenario, options.limits);
  const Time max_time = limits.max_time ? std::min(*limits.max_time, scenario.max_time) : scenario.max_time;
  master::MasterParams master_params = scenario.master;
  master_params.seed = options.seed.value_or(scenario.seed);
  checker::CheckerParams checker_params = scenario.checker;
  checker_params.max_findings_per_check = std::min(checker_params.max_findings_per_check, options.kept);

  ScenarioResult r;
  r.file = scenario.file;
  r.name = scenario.name;
  r.description = scenario.description;
  r.field = scenario.field;
  r.seed = master_params.seed;
  r.f_c = master_params.f_c;
  r.position_bits = scenario.encoder.position_bits;
  r.multiturn_bits = scenario.encoder.multiturn_bits;

  sim::Kernel kernel;
  line::Line line(kernel, scenario.line);
  slave::Encoder encoder(kernel, line, scenario.encoder);
  std::vector<std::unique_ptr<slave::Encoder>> bus;
  for (const auto& p : scenario.bus) bus.push_back(std::make_unique<slave::Encoder>(kernel, line.add_encoder(), p));
  master::Master master(kernel, line, master_params);
  master::MasterFunctions functions(master);
  checker::TimingChecker checker(kernel, line, declared_encoder(scenario.encoder), declared_master(master_params),
                                 checker_params);
  if (options.kept != SIZE_MAX) {
    // The encoder frames a master frame is matched with are among the last few.
    constexpr std::size_t kEncoderWindow = 64;
    master.keep_frames(options.kept);
    encoder.keep_frames(std::max(options.kept, kEncoderWindow));
    for (const auto& e : bus) e->keep_frames(std::max(options.kept, kEncoderWindow));
  }
  MasterDeclarations declarations(checker);
  master.add_observer(&declarations);
  RunRecorder recorder(scenario, functions.safety(), encoder, checker, r, options.sinks);
  master.add_observer(&recorder);
  checker.set_finding_listener([&recorder](const checker::Violation& v) { recorder.on_finding(v); });

  std::unique_ptr<sim::VcdWriter> vcd;
  std::unique_ptr<DecodedTrace> decoded;
  if (options.vcd_path) {
    vcd = std::make_unique<sim::VcdWriter>(kernel, *options.vcd_path);
    add_pin_waves(*vcd, line);
    vcd->add(master.sample_strobe(), std::string(kWaveformScope), "master_sample");
    vcd->add(master.frame_active(), std::string(kWaveformScope), "master_frame");
    if (options.vcd_decoded) {
      decoded = std::make_unique<DecodedTrace>(*vcd);
      master.add_observer(decoded.get());
    }
    vcd->start();
  }
  r.conformance = checker.conformance();  // the rows relaxed, for the outputs' heads
  for (RunSink* sink : options.sinks) sink->begin(r);

  for (const auto& op : scenario.script) master.enqueue(op);
  EventDriver events(kernel, line, encoder, &master, checker, scenario.events, master_params.seed,
                     sim::period_of(master_params.f_c));
  master.start();
  Watch watch(kernel, master, encoder, bus, checker, limits);
  watch.progress = options.progress;
  if (options.progress != nullptr) options.progress->end_ps.store(max_time.count(), std::memory_order_relaxed);
  // Each record takes at least one event: looking as often as the lowest limit sees every one reached.
  kernel.watch(std::min({Watch::kEvery, limits.kernel_events, limits.records}), sim::bind<&Watch::check>(&watch));
  LimitRoom room(kernel, watch, limits);
  std::optional<FrameReplay> replay;
  if (options.engine != Engine::Event && bus.empty())
    replay.emplace(kernel, line, master, encoder, events, room, declarations, vcd.get());
  kernel.run(max_time);
  if (watch.reason.empty() && max_time < scenario.max_time && !master.finished() && kernel.now() >= max_time)
    watch.reason = "limit max_time reached: " + sim::format_time(max_time) + " simulated, less than the scenario's " +
                   sim::format_time(scenario.max_time) + " (" + kMaxTimeOption + " changes it)";
  if (!master.finished()) checker.end_run_early(kernel.now());
  checker.finish();
  recorder.finish();
  if (vcd) vcd->finish();

  r.simulated = kernel.now();
  r.events = kernel.events_processed();
  r.frames_replayed = replay ? replay->frames_replayed() : 0;
  r.events_not_acted = events.not_acted();
  r.finished = master.finished();
  r.incomplete = watch.reason;
  r.interrupted = watch.interrupted;
  r.true_round_trip = line.round_trip(scenario.encoder.output_delay);
  r.frames = master.frames();
  r.measurements = master.measurements();
  r.measurements_count = master.measurements_count();
  r.last_measurement = master.last_measurement();
  r.encoder_frames = encoder.frames();
  r.violations = checker.violations();
  r.conclusion = checker.conclusion();
  r.conformance = checker.conformance();
  r.cycle_overruns = master.cycle_overruns();
  r.busy_timeouts = master.busy_timeouts();
  r.busy_unreadable = master.busy_unreadable();
  r.startup = master.startup();
  r.checksum = master.checksum();
  r.retries = master.retries();
  r.remeasurements = master.remeasurements();
  r.safety = functions.safety();
  if (scenario.master.diagnostics.enabled) r.diagnosis = functions.diagnosis();
  r.encoder_memory = encoder.memory().image();
  for (const auto& e : bus) {
    r.bus_memory.push_back(e->memory().image());
    r.bus_frames.push_back(e->frames());
  }
  judge(scenario, r);
  for (RunSink* sink : options.sinks) sink->end(r);
  return r;
}

}  // namespace endatsim::scenarios

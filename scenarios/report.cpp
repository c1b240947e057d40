#include "endatsim/scenarios/report.hpp"

#include "endatsim/capture/capture.hpp"
#include "endatsim/protocol/parameters.hpp"
#include "endatsim/sim/text.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <span>

namespace endatsim::scenarios {
namespace {

using sim::format_time;

// A multiturn position: the upper multiturn_bits count revolutions (2.3.1 / word 13).
std::pair<std::uint64_t, std::uint64_t> revolution_and_singleturn(const ScenarioResult& r, std::uint64_t position) {
  const unsigned singleturn_bits = r.position_bits - r.multiturn_bits;
  return {position >> singleturn_bits, position & ((std::uint64_t{1} << singleturn_bits) - 1)};
}

std::string frame_line(const ScenarioResult& r, const master::FrameResult& f) {
  std::string s = "  #" + std::to_string(f.index) + (f.word > 0 ? " word " + std::to_string(f.word) : "") + " " +
                  format_time(f.start) + " " +
                  std::string(protocol::info(f.command).key) + " @ " + sim::format_frequency(f.f_c) + ": " +
                  std::string(master::to_string(f.outcome));
  // A position and F1 belong to a position answer; an echo or a test value has neither.
  const bool position = protocol::info(f.command).answer == protocol::AnswerFormat::Position;
  if (f.outcome == master::FrameOutcome::CrcError && !position)
    s += ", CRC " + std::to_string(f.crc_received) + " != " + std::to_string(f.crc_expected);
  if (position && (f.outcome == master::FrameOutcome::Ok || f.outcome == master::FrameOutcome::CrcError)) {
    s += ", position " + std::to_string(f.position);
    if (r.multiturn_bits > 0) {
      const auto [rev, st] = revolution_and_singleturn(r, f.position);
      s += " (revolution " + std::to_string(rev) + ", singleturn " + std::to_string(st) + ")";
    }
    s += ", F1 " + std::to_string(f.error1);
    if (f.outcome == master::FrameOutcome::CrcError)
      s += ", CRC " + std::to_string(f.crc_received) + " != " + std::to_string(f.crc_expected);
  }
  if (f.measurement && f.delay_count_time) s += ", counter " + format_time(*f.delay_count_time);
  return s;
}

}  // namespace

std::string hex4(std::uint16_t v) { return sim::hex_h(v, 4); }

// What the master's start-up routine (docs/model.md §8) read, decoded (3.4, 3.5.6, 3.5.22).
void write_startup(std::ostream& out, const master::StartupInfo& s) {
  namespace pm = protocol::parameters;
  if (!s.completed && s.failed_frames == 0 && !s.word13) return;
  out << "  start-up routine: " << (s.completed ? "completed" : std::to_string(s.failed_frames) + " frames failed");
  if (s.errors) out << "; alarms " << hex4(*s.errors);
  if (s.warnings) out << ", warnings " << hex4(*s.warnings);
  if (s.word13) out << "; word 13 " << hex4(*s.word13) << " (" << pm::decode_position_bits(*s.word13) << " position bits)";
  if (s.word37) out << "; word 37 " << hex4(*s.word37) << " (" << pm::command_set_string(*s.word37) << ")";
  out << "\n";
}

// What the careful master did and what its checksum check found (3.5.26).
void write_careful_master(std::ostream& out, const ScenarioResult& r) {
  if (r.retries != 0 || r.remeasurements != 0)
    out << "  careful master: " << r.retries << " frame(s) repeated, " << r.remeasurements
        << " delay measurement(s) added\n";
  if (!r.checksum) return;
  out << "  checksum (word 47): ";
  if (!r.checksum->complete) out << "not every word could be read\n";
  else out << (r.checksum->ok() ? "ok" : "MISMATCH") << ", stored " << hex4(r.checksum->stored) << ", words 4 .. 46 sum to "
           << hex4(r.checksum->computed) << "\n";
}

// What the safety functions found and decided, for a safety assessment.
void write_safety(std::ostream& out, const ScenarioResult& r, bool verbose) {
  namespace pm = protocol::parameters;
  const auto& s = r.safety;
  if (s.findings.empty() && !s.axis_released && s.startup_reads == 0 && s.position_comparisons == 0) return;
  out << "  safety: axis " << (s.axis_released ? "released at " + format_time(s.released_at) + " with position " +
                                                     std::to_string(s.release_position)
                                               : std::string("not released"));
  if (s.startup_reads != 0) out << " after " << s.startup_reads << " start-up read(s)";
  if (r.release_position_correct) out << (*r.release_position_correct ? " (as measured)" : " (NOT what the encoder measured)");
  out << "\n";
  if (s.checksum47_stored)
    out << "    checksums: word 47 " << hex4(*s.checksum47_stored) << " (sum " << hex4(*s.checksum47_computed) << ")";
  if (s.checksum63_stored)
    out << ", word 63 " << hex4(*s.checksum63_stored) << " (sum " << hex4(*s.checksum63_computed) << ")";
  if (s.checksum47_stored) out << "\n";
  if (s.position_comparisons != 0 || s.comparisons_out_of_range != 0)
    out << "    position value 2 compared " << s.position_comparisons << " time(s), " << s.comparisons_out_of_range
        << " above the stored velocity ranges\n";
  if (s.error_sources) out << "    word 0 after the error message: " << hex4(*s.error_sources) << " (" << pm::bits_string(*s.error_sources, pm::error_bit_names()) << ")\n";
  if (s.operating_status_error_sources)
    out << "    operating status error sources (additional data 2): " << hex4(*s.operating_status_error_sources) << "\n";
  if (r.undetected_errors != 0) out << "    " << r.undetected_errors << " frame(s) read as good while the encoder had an error\n";
  const std::size_t limit = verbose ? s.findings.size() : 5;
  for (std::size_t i = 0; i < s.findings.size() && i < limit; ++i) {
    const auto& f = s.findings[i];
    out << "    finding " << master::to_string(f.function) << " at " << format_time(f.at);
    if (f.frame) out << " (frame #" << *f.frame << ")";
    out << ": " << f.message << "\n";
  }
  if (s.findings.size() > limit) out << "    ... " << s.findings.size() - limit << " more finding(s)\n";
}

std::string numbers_of(std::uint16_t bits) {
  std::string s;
  for (unsigned k = 0; k < protocol::diagnosis::kValuationNumbers; ++k)
    if (((bits >> k) & 1U) != 0) s += (s.empty() ? "" : " ") + std::to_string(k + 1);
  return s.empty() ? "none" : s;
}

std::string range_of(const master::DiagnosisReading& x, bool temperature) {
  namespace dg = protocol::diagnosis;
  const auto show = [temperature](unsigned v) { return temperature ? dg::temperature_string(v) : std::to_string(v); };
  std::string s = show(x.last);
  if (x.min != x.max) s += ", range " + show(x.min) + " .. " + show(x.max);
  return s + ", " + std::to_string(x.count) + " reading(s)";
}

// What the master's diagnosis collected (appendix A3), for a service engineer.
void write_diagnosis(std::ostream& out, const ScenarioResult& r, bool verbose) {
  namespace pm = protocol::parameters;
  namespace dg = protocol::diagnosis;
  if (!r.diagnosis) return;
  const auto& d = *r.diagnosis;
  out << "  diagnosis (appendix A3):";
  if (d.diagnostic_status) out << " supported valuation numbers " << numbers_of(*d.diagnostic_status) << " (word 5)";
  if (d.configuration) {
    out << ", activated " << numbers_of(*d.configuration) << " (word 3";
    if ((*d.configuration & dg::kSystemSpecificDataBit) != 0) out << ", with system-specific data";
    if (d.configuration_written) out << ", written " << hex4(*d.configuration_written) << " and reset";
    out << ")";
  }
  out << "\n";
  for (const auto& [address, x] : d.valuation_numbers) {
    const auto a = dg::decode_diagnosis_address(address);
    out << "    valuation number " << (a ? a->bit + 1 : 0) << " (address " << address << "): " << range_of(x, false) << "\n";
  }
  if (d.temperature1) out << "    temperature 1 (external, leading): " << range_of(*d.temperature1, true) << "\n";
  if (d.temperature2) out << "    temperature 2 (on board): " << range_of(*d.temperature2, true) << "\n";
  for (const auto& [address, x] : d.additional_sensors)
    out << "    additional sensor " << address << ": " << range_of(x, true) << "\n";
  if (d.warning_threshold || d.max_temperature) {
    out << "    limits:";
    if (d.warning_threshold) out << " warning threshold " << (*d.warning_threshold != 0 ? dg::temperature_string(*d.warning_threshold) : "none") << " (word 6)";
    if (d.max_temperature) out << (d.warning_threshold ? "," : "") << " maximum " << (*d.max_temperature != 0 ? dg::temperature_string(*d.max_temperature) : "not given") << " (word 22)";
    out << "\n";
  }
  if (d.ignored_addresses != 0) out << "    " << d.ignored_addresses << " diagnosis value(s) at undefined or system-specific addresses ignored\n";
  if (d.warning_bit_at) {
    out << "    WRN first at " << format_time(*d.warning_bit_at) << " (frame #" << *d.warning_bit_frame << ")";
    if (d.warnings) out << "; word 1 = " << hex4(*d.warnings) << " (" << pm::bits_string(*d.warnings, pm::warning_bit_names()) << ")";
    out << "\n";
  }
  const std::size_t limit = verbose ? d.notes.size() : 8;
  for (std::size_t i = 0; i < d.notes.size() && i < limit; ++i) {
    const auto& n = d.notes[i];
    out << "    note " << master::to_string(n.kind) << " at " << format_time(n.at);
    if (n.frame) out << " (frame #" << *n.frame << ")";
    out << ": " << n.message << "\n";
  }
  if (d.notes.size() > limit) out << "    ... " << d.notes.size() - limit << " more note(s)\n";
}

void write_relaxations(std::ostream& out, const std::vector<checker::RowConformance>& rows) {
  for (const auto& c : rows)
    if (!c.relaxed_by.empty()) out << "  relaxed by option: " << c.check << " (" << c.relaxed_by << ")\n";
}

void write_conformance(std::ostream& out, const std::vector<checker::RowConformance>& rows) {
  out << "  conformance (row: judged / violations / warnings [/ undecided], or why not judged):\n";
  for (const auto& c : rows) {
    out << "    " << c.check << ": ";
    if (c.status == checker::RowConformance::Status::Judged) {
      out << c.judged << " / " << c.violations << " / " << c.warnings;
      if (c.undecided != 0) out << " / " << c.undecided;
      out << (c.violations != 0 ? "  BROKEN" : c.undecided != 0 ? "  UNDECIDED" : "  ok");
      for (std::size_t k = 0; k < c.worst.size(); ++k) {
        const checker::WorstCase& w = c.worst[k];
        out << (k == 0 ? "; worst " : "; ") << w.measured << " against " << w.limit << " ("
            << checker::to_string(w.of) << "), margin " << w.margin;
      }
      // A frequency is shown before the oscillator's allowance: a worst case outside its bound
      // that broke nothing passed by that allowance, which the line names.
      namespace check = checker::check;
      const bool frequency = c.check == check::kClockFrequency || c.check == check::kMeasurementClock ||
                             c.check == check::kShortRecoveryClock;
      if (frequency && c.violations + c.warnings + c.undecided == 0 &&
          std::any_of(c.worst.begin(), c.worst.end(), [](const checker::WorstCase& w) { return !w.inside; }))
        out << " (within the oscillator allowance, f_c_tolerance_ppm)";
    } else {
      out << checker::to_string(c.status) << " (" << c.reason << ")";
    }
    out << "\n";
  }
}

nlohmann::json conformance_json(const std::vector<checker::RowConformance>& rows) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& c : rows) {
    nlohmann::json j{{"check", c.check}, {"status", std::string(checker::to_string(c.status))}, {"judged", c.judged},
                     {"violations", c.violations}, {"warnings", c.warnings}, {"undecided", c.undecided}};
    if (!c.reason.empty()) j["reason"] = c.reason;
    if (!c.relaxed_by.empty()) j["relaxed_by"] = c.relaxed_by;
    for (const checker::WorstCase& w : c.worst)
      j["worst"].push_back({{"limit_of", std::string(checker::to_string(w.of))}, {"measured", w.measured},
                            {"limit", w.limit}, {"margin", w.margin}, {"inside", w.inside}});
    out.push_back(j);
  }
  return out;
}

nlohmann::json violations_json(const std::vector<checker::Violation>& violations) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& v : violations) {
    nlohmann::json j{{"check", v.check},
                     {"spec", v.spec},
                     {"where", std::string(line::to_string(v.where))},
                     {"time_ps", v.time.count()},
                     {"measured", v.measured},
                     {"limit", v.limit},
                     {"severity", std::string(checker::to_string(v.severity))},
                     {"verdict", std::string(checker::to_string(v.verdict))},
                     {"message", v.message}};
    if (v.frame) j["frame"] = *v.frame;
    if (v.clock) j["clock"] = *v.clock;
    if (!v.field.empty()) j["field"] = v.field;
    out.push_back(j);
  }
  return out;
}

// A decided verdict as a boolean; one that only undecided findings count against as "undecided".
nlohmann::json verdict_json(const checker::Conclusion& c) {
  const auto verdict = [](bool no_error, bool undecided) {
    return no_error && undecided ? nlohmann::json("undecided") : nlohmann::json(no_error);
  };
  return {{"spec_envelope", verdict(c.spec_envelope, c.spec_envelope_undecided)},
          {"this_encoder", verdict(c.this_encoder, c.this_encoder_undecided)}};
}

namespace {

// The checks whose findings of `severity` count against the spec envelope only, with their first
// measured value and limit.
std::string envelope_only(const std::vector<checker::Violation>& violations, checker::Severity severity) {
  std::string out;
  std::set<std::string> shown;
  for (const auto& v : violations)
    if (v.severity == severity && v.verdict == checker::Verdict::SpecEnvelope && shown.insert(v.check).second)
      out += " " + v.check + " " + v.measured + " (" + v.limit + ")";
  return out;
}

}  // namespace

// "conforms to this encoder; outside the spec envelope: t_m_t_r 11 us (>= 30.5 us (spec envelope))".
// A verdict that only undecided findings count against reads "undecided at this resolution".
void write_verdict(std::ostream& out, const checker::Conclusion& c, const std::vector<checker::Violation>& violations) {
  out << "  verdict: ";
  if (c.conforms_to_spec_envelope() && c.conforms_to_this_encoder()) {
    out << "conforms to the spec envelope and to this encoder\n";
    return;
  }
  const std::string envelope = c.spec_envelope ? "undecided at this resolution for the spec envelope" : "";
  if (!c.this_encoder) {
    out << "does not conform to this encoder";
    if (!c.spec_envelope) out << " nor to the spec envelope\n";
    else if (c.spec_envelope_undecided) out << "; " << envelope << "\n";
    else out << " (its declared limits); within the spec envelope\n";
    return;
  }
  if (c.this_encoder_undecided && c.spec_envelope && c.spec_envelope_undecided) {
    out << "undecided at this resolution for the spec envelope and for this encoder\n";
    return;
  }
  out << (c.this_encoder_undecided ? "undecided at this resolution for this encoder" : "conforms to this encoder");
  if (!c.spec_envelope) {
    out << "; outside the spec envelope:" << envelope_only(violations, checker::Severity::Error);
  } else if (c.spec_envelope_undecided) {
    const std::string which = envelope_only(violations, checker::Severity::Undecided);
    out << "; " << envelope << (which.empty() ? "" : ":" + which);
  } else {
    out << "; conforms to the spec envelope";
  }
  out << "\n";
}

void write_violations(std::ostream& out, const std::vector<checker::Violation>& violations,
                      const std::vector<checker::RowConformance>& rows, bool verbose) {
  std::map<std::string, std::vector<const checker::Violation*>> by_check;
  for (const auto& v : violations) by_check[v.check].push_back(&v);
  const auto counts = finding_counts(rows);
  for (const auto& [check, list] : by_check) {
    const auto it = counts.find(check);
    const std::uint64_t n = it == counts.end() ? list.size() : std::max<std::uint64_t>(it->second, list.size());
    out << "  violation " << check << " x" << n << " [" << list.front()->spec << "]\n";
    const std::size_t limit = verbose ? list.size() : 3;
    for (std::size_t i = 0; i < list.size() && i < limit; ++i) {
      const auto& v = *list[i];
      out << "    " << checker::to_string(v.severity) << " at " << format_time(v.time) << " ("
          << line::to_string(v.where);
      if (v.frame) out << ", frame #" << *v.frame;
      if (v.clock) out << ", clock " << *v.clock;
      if (!v.field.empty()) out << ", " << v.field;
      out << "): measured " << v.measured << ", limit " << v.limit << " - " << v.message;
      if (v.verdict != checker::Verdict::Both) out << " [" << checker::to_string(v.verdict) << " only]";
      out << "\n";
    }
    if (verbose && n > list.size()) out << "    ... " << n - list.size() << " more, counted but not kept (--examples)\n";
  }
}

// What the master could not do as the script asked, whether or not an expectation counts it.
void write_master_warnings(std::ostream& out, const ScenarioResult& r) {
  if (r.cycle_overruns != 0)
    out << "  warning: " << r.cycle_overruns << " frame(s) started late: the read cycle could not be kept (the frame "
        << "before, its recovery time or a retry took longer than the cycle)\n";
  if (r.busy_timeouts != 0)
    out << "  warning: " << r.busy_timeouts << " await_not_busy gave up: the busy bit stayed set for max_polls polls\n";
  if (r.busy_unreadable != 0)
    out << "  warning: " << r.busy_unreadable << " await_not_busy could not read the busy bit: its poll frames carried "
        << "no additional data 1, which holds it (D297403 2.5.1); select additional data 1 first\n";
}

void write_events_not_acted(std::ostream& out, const std::vector<EventNotActed>& events) {
  constexpr std::size_t kShown = 3;
  for (std::size_t i = 0; i < events.size() && i < kShown; ++i)
    out << "  warning: event #" << events[i].index << " (" << events[i].kind << ", " << events[i].when
        << ") never acted: the run ended before it\n";
  if (events.size() > kShown) out << "  ... " << events.size() - kShown << " more event(s) never acted\n";
}

nlohmann::json events_not_acted_json(const std::vector<EventNotActed>& events) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& e : events) out.push_back({{"index", e.index}, {"kind", e.kind}, {"when", e.when}});
  return out;
}

void write_summary(std::ostream& out, const ScenarioResult& r, bool verbose) {
  out << (r.passed() ? "PASS " : "FAIL ") << r.name << " (" << r.file << ", seed " << r.seed << ")\n";
  if (!r.incomplete.empty()) out << "  INCOMPLETE: " << r.incomplete << "\n";
  write_events_not_acted(out, r.events_not_acted);
  // A scenario's free texts go to a terminal: control bytes (an escape sequence, a carriage return
  // that forges a line) are shown escaped, never sent.
  using capture::printable;
  if (!r.description.empty()) out << "  " << printable(r.description) << "\n";
  if (r.field) {
    out << "  field symptom: " << printable(r.field->symptom) << "\n  cause: " << printable(r.field->cause)
        << "\n  spec: " << printable(r.field->spec) << "\n  asserts: " << printable(r.field->asserts) << "\n";
  }
  std::map<std::string, std::uint64_t> outcomes;  // by name
  for (const master::FrameOutcome o : master::kFrameOutcomes)
    if (r.tally.outcome(o) != 0) outcomes[std::string(master::to_string(o))] = r.tally.outcome(o);
  out << "  simulated " << format_time(r.simulated) << ", " << r.events << " events; frames: " << r.tally.frames() << " (";
  bool first = true;
  for (const auto& [name, n] : outcomes) {
    out << (first ? "" : ", ") << name << " " << n;
    first = false;
  }
  out << "), delay-measurement frames: " << r.tally.measurement_frames << "\n";
  // Three, as of each check's findings (--verbose: every one kept), so that the summary does not
  // depend on how many were kept.
  const std::size_t shown = verbose ? r.measurements.size() : std::min<std::size_t>(r.measurements.size(), 3);
  for (const auto& m : std::span(r.measurements).first(shown)) {
    out << "  t_D measurement (round " << m.rounds << "): ";
    if (m.accepted) out << "accepted, t_D = " << format_time(m.t_d);
    else out << "rejected: " << m.reason;
    out << "; counts";
    for (auto c : m.counts) out << " " << c;
    out << " x " << format_time(m.counter_period) << "; true round trip " << format_time(r.true_round_trip) << "\n";
  }
  if (r.measurements_count > shown)
    out << "  ... " << r.measurements_count - shown << " more t_D measurement(s)"
        << (verbose && r.measurements_count > r.measurements.size() ? ", counted but not kept (--examples)" : "") << "\n";
  for (const auto& f : verbose ? r.frames : r.tally.failed) out << frame_line(r, f) << "\n";
  if (verbose && r.tally.results > r.frames.size())
    out << "  ... " << r.tally.results - r.frames.size() << " more frames, not kept (--log lists every one)\n";
  write_startup(out, r.startup);
  write_careful_master(out, r);
  write_safety(out, r, verbose);
  write_diagnosis(out, r, verbose);
  if (!verbose && r.tally.first_position)
    out << "  first position read: " << r.tally.first_position->position << " (frame #" << r.tally.first_position->index
        << ")\n";
  write_master_warnings(out, r);
  write_violations(out, r.violations, r.conformance, verbose);
  if (!r.violations.empty() || verbose) write_verdict(out, r.conclusion, r.violations);
  write_relaxations(out, r.conformance);
  if (verbose) write_conformance(out, r.conformance);
  for (const auto& e : r.expectations)
    if (verbose || !e.passed) out << "  " << (e.passed ? "ok   " : "FAIL ") << e.name << ": " << e.detail << "\n";
}

namespace {

// A parameter word that was read, or nothing when it was not.
void put_word(nlohmann::json& j, const char* key, const std::optional<std::uint16_t>& v) {
  if (v) j[key] = *v;
}

nlohmann::json reading_json(const master::DiagnosisReading& x) {
  return {{"last", x.last}, {"min", x.min}, {"max", x.max}, {"count", x.count}, {"first_ps", x.first_at.count()},
          {"last_ps", x.last_at.count()}};
}

// Temperatures stay in 0.1 K as the encoder sends them (3.9.6); celsius = (value - 2731) / 10.
nlohmann::json diagnosis_json(const master::DiagnosisReport& d) {
  using nlohmann::json;
  json j{{"ignored_addresses", d.ignored_addresses}};
  put_word(j, "additional_data_1_support", d.additional_data_1_support);
  put_word(j, "temperature_scaling", d.temperature_scaling);
  put_word(j, "diagnostic_status", d.diagnostic_status);
  put_word(j, "max_temperature", d.max_temperature);
  put_word(j, "supported_warnings", d.supported_warnings);
  put_word(j, "configuration", d.configuration);
  put_word(j, "configuration_written", d.configuration_written);
  put_word(j, "warning_threshold", d.warning_threshold);
  put_word(j, "warnings", d.warnings);
  json vn = json::object();
  for (const auto& [address, x] : d.valuation_numbers) vn[std::to_string(address)] = reading_json(x);
  j["valuation_numbers"] = vn;
  if (d.temperature1) j["temperature_1"] = reading_json(*d.temperature1);
  if (d.temperature2) j["temperature_2"] = reading_json(*d.temperature2);
  json sensors = json::object();
  for (const auto& [address, x] : d.additional_sensors) sensors[std::to_string(address)] = reading_json(x);
  j["additional_sensors"] = sensors;
  if (d.warning_bit_at) {
    j["warning_bit_ps"] = d.warning_bit_at->count();
    j["warning_bit_frame"] = *d.warning_bit_frame;
  }
  json notes = json::array();
  for (const auto& n : d.notes) {
    json jn{{"kind", master::to_string(n.kind)}, {"time_ps", n.at.count()}, {"message", n.message}};
    if (n.frame) jn["frame"] = *n.frame;
    notes.push_back(jn);
  }
  j["notes"] = notes;
  return j;
}

}  // namespace

JsonTokens frame_tokens(const ScenarioResult& r, const master::FrameResult& f) {
  JsonTokens jf;
  jf.begin_object();
  jf.member("index", f.index);
  jf.member("word", f.word);
  jf.member("start_ps", f.start.count());
  jf.member("end_ps", f.end.count());
  jf.member("command", protocol::info(f.command).key);
  jf.member("mode_bits", f.mode_bits);
  jf.member("f_c_hz", f.f_c);
  jf.member("measurement", f.measurement);
  jf.member("compensated", f.compensated);
  jf.member("t_d_used_ps", f.t_d_used.count());
  jf.member("outcome", master::to_string(f.outcome));
  jf.member("clocks", f.clocks);
  jf.member("start_bit_clock", f.start_bit_clock);
  if (f.outcome == master::FrameOutcome::Ok || f.outcome == master::FrameOutcome::CrcError) {
    jf.member("position", f.position);
    if (r.multiturn_bits > 0) {
      const auto [rev, st] = revolution_and_singleturn(r, f.position);
      jf.member("revolution", rev);
      jf.member("singleturn", st);
    }
    jf.member("error1", f.error1);
    jf.member("error2", f.error2);
    jf.member("error_detected", f.error_detected);
    jf.member("crc_received", f.crc_received);
    jf.member("crc_expected", f.crc_expected);
  }
  // Each additional datum with its own CRC: a frame can fail on one while the position's agrees.
  if (!f.additional_data.empty()) {
    jf.key("additional_data").begin_array();
    for (const auto& d : f.additional_data) {
      jf.begin_object();
      jf.member("information", protocol::info(d.information()).key);
      jf.member("additional_data", protocol::is_additional_data_2(d.information()) ? 2 : 1);
      jf.member("status", d.status);
      jf.member("data", d.data);
      jf.member("busy", d.busy());
      jf.member("crc_received", d.crc_received);
      jf.member("crc_expected", d.crc_expected);
      jf.member("crc_ok", d.crc_ok);
      jf.end_object();
    }
    jf.end_array();
  }
  jf.end_object();
  return jf;
}

nlohmann::json frame_json(const ScenarioResult& r, const master::FrameResult& f) { return frame_tokens(r, f).sorted(); }

nlohmann::json result_json_without_frames(const ScenarioResult& r) {
  using nlohmann::json;
  json j;
  j["name"] = r.name;
  j["file"] = r.file;
  j["seed"] = r.seed;
  if (r.field)
    j["field"] = {{"symptom", r.field->symptom}, {"cause", r.field->cause}, {"spec", r.field->spec},
                  {"asserts", r.field->asserts}};
  j["passed"] = r.passed();
  if (!r.incomplete.empty()) {
    j["complete"] = false;
    j["incomplete"] = r.incomplete;
  }
  j["simulated_ps"] = r.simulated.count();
  j["events"] = r.events;
  if (!r.events_not_acted.empty()) j["events_not_acted"] = events_not_acted_json(r.events_not_acted);
  j["true_round_trip_ps"] = r.true_round_trip.count();
  json ms = json::array();
  for (const auto& m : r.measurements) {
    json jm{{"accepted", m.accepted}, {"rounds", m.rounds}, {"counts", m.counts},
            {"counter_period_ps", m.counter_period.count()}};
    if (m.accepted) jm["t_d_ps"] = m.t_d.count();
    else jm["reason"] = m.reason;
    ms.push_back(jm);
  }
  j["delay_measurements"] = ms;  // the first kept
  if (r.measurements_count > r.measurements.size()) j["delay_measurements_not_kept"] = r.measurements_count - r.measurements.size();
  j["retries"] = r.retries;
  j["remeasurements"] = r.remeasurements;
  j["cycle_overruns"] = r.cycle_overruns;
  j["busy_timeouts"] = r.busy_timeouts;
  j["busy_unreadable"] = r.busy_unreadable;
  if (r.checksum)
    j["checksum"] = {{"complete", r.checksum->complete}, {"ok", r.checksum->ok()}, {"stored", r.checksum->stored},
                     {"computed", r.checksum->computed}};
  if (r.startup.completed || r.startup.failed_frames != 0) {
    json st;
    st["completed"] = r.startup.completed;
    put_word(st, "errors", r.startup.errors);
    put_word(st, "warnings", r.startup.warnings);
    put_word(st, "word13", r.startup.word13);
    put_word(st, "word37", r.startup.word37);
    j["startup"] = st;
  }
  {
    const auto& s = r.safety;
    json findings = json::array();
    for (const auto& f : s.findings) {
      json jf{{"function", master::to_string(f.function)}, {"time_ps", f.at.count()}, {"message", f.message}};
      if (f.frame) jf["frame"] = *f.frame;
      findings.push_back(jf);
    }
    json js{{"findings", findings},
            {"axis_released", s.axis_released},
            {"startup_reads", s.startup_reads},
            {"position_comparisons", s.position_comparisons},
            {"comparisons_out_of_range", s.comparisons_out_of_range},
            {"undetected_errors", r.undetected_errors}};
    if (s.axis_released) {
      js["released_ps"] = s.released_at.count();
      js["release_position"] = s.release_position;
    }
    if (r.release_position_correct) js["release_position_correct"] = *r.release_position_correct;
    put_word(js, "error_sources", s.error_sources);
    put_word(js, "operating_status_error_sources", s.operating_status_error_sources);
    put_word(js, "checksum47_stored", s.checksum47_stored);
    put_word(js, "checksum47_computed", s.checksum47_computed);
    put_word(js, "checksum63_stored", s.checksum63_stored);
    put_word(js, "checksum63_computed", s.checksum63_computed);
    j["safety"] = js;
  }
  if (r.diagnosis) j["diagnosis"] = diagnosis_json(*r.diagnosis);
  j["violations"] = violations_json(r.violations);
  // Findings counted in the conformance table beyond the ones listed (RunOptions::kept).
  std::uint64_t counted = 0;
  for (const auto& [check, n] : finding_counts(r.conformance)) counted += n;
  if (counted > r.violations.size()) j["violations_not_kept"] = counted - r.violations.size();
  j["verdict"] = verdict_json(r.conclusion);
  j["conformance"] = conformance_json(r.conformance);
  json es = json::array();
  for (const auto& e : r.expectations) es.push_back({{"name", e.name}, {"passed", e.passed}, {"detail", e.detail}});
  j["expectations"] = es;
  return j;
}

nlohmann::json to_json(const ScenarioResult& r) {
  nlohmann::json j = result_json_without_frames(r);
  nlohmann::json frames = nlohmann::json::array();
  for (const auto& f : r.frames) frames.push_back(frame_json(r, f));
  j["frames"] = frames;
  return j;
}

}  // namespace endatsim::scenarios

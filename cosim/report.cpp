#include "endatsim/cosim/report.hpp"

#include "endatsim/scenarios/capture_check.hpp"
#include "endatsim/scenarios/exit_status.hpp"
#include "endatsim/scenarios/interrupt.hpp"
#include "endatsim/scenarios/junit.hpp"
#include "endatsim/scenarios/output_file.hpp"
#include "endatsim/scenarios/report.hpp"

namespace endatsim::cosim {

namespace exit_status = scenarios::exit_status;
namespace {

nlohmann::json reported_json(const std::vector<Reported>& reported) {
  auto out = nlohmann::json::array();
  for (const auto& r : reported)
    out.push_back({{"at_ps", r.at.count()},
                   {"value", r.value},
                   {"expected", r.truth ? nlohmann::json(*r.truth) : nlohmann::json(nullptr)},
                   {"matches", r.matches()}});
  return out;
}

std::string testcase(const std::string& name, const std::string& file, const std::string& inner) {
  return "    <testcase classname=\"endatsim.cosim\" name=\"" + scenarios::xml_escape(name) + "\" file=\"" +
         scenarios::xml_escape(file) + "\">\n" + inner + "    </testcase>\n";
}

nlohmann::json cut_frame_json(const BenchResult& r) {
  return {{"frame", *r.frame_cut_by_end},
          {"clock", r.clock_at_end ? 1 : 0},
          {"clock_since_ps", r.clock_last_change.count()}};
}

// A frame the simulation's end cut: what was not judged, and how long CLOCK had stood still.
std::string cut_frame_text(const BenchResult& r) {
  return "the simulation ended inside frame #" + std::to_string(*r.frame_cut_by_end) +
         ": its clock count and start-bit polling not judged; CLOCK " + (r.clock_at_end ? "HIGH" : "LOW") +
         " at the encoder's connector since " + sim::format_time(r.clock_last_change) + " (" +
         sim::format_time(r.simulated - r.clock_last_change) + " before the end)";
}

}  // namespace

void write_summary(std::ostream& out, const BenchResult& r, bool verbose) {
  out << (r.passed() ? "PASS " : "FAIL ") << r.name << " (" << r.file << ", seed " << r.seed << ")\n";
  if (!r.description.empty()) out << "  " << r.description << "\n";
  out << "  simulated " << sim::format_time(r.simulated) << ", " << r.events << " events; frames decoded at the "
      << "encoder's connector: " << r.frames_decoded << " (" << r.frames_clean << " with a complete answer and a good CRC)\n";
  out << "  the master reported " << r.positions.size() << " position(s) and " << r.parameters.size()
      << " parameter(s); judged from the wires alone (the master declares nothing)\n";
  for (const auto& n : r.notes) out << "  note: " << n << "\n";
  if (!r.incomplete.empty()) out << "  INCOMPLETE: " << r.incomplete << "\n";
  scenarios::write_events_not_acted(out, r.events_not_acted);
  if (r.frame_cut_by_end) out << "  " << cut_frame_text(r) << "\n";
  if (verbose)
    for (const auto& f : r.frames) out << "  " << scenarios::frame_log_line(f);
  scenarios::write_violations(out, r.violations, r.conformance, verbose);
  scenarios::write_verdict(out, r.conclusion, r.violations);
  scenarios::write_relaxations(out, r.conformance);
  if (verbose) scenarios::write_conformance(out, r.conformance);
  for (const auto& e : r.expectations)
    if (verbose || !e.passed) out << "  " << (e.passed ? "ok   " : "FAIL ") << e.name << ": " << e.detail << "\n";
}

nlohmann::json to_json(const BenchResult& r) {
  using nlohmann::json;
  json expectations = json::array();
  for (const auto& e : r.expectations) expectations.push_back({{"name", e.name}, {"passed", e.passed}, {"detail", e.detail}});
  json j{{"name", r.name},
          {"file", r.file},
          {"seed", r.seed},
          {"passed", r.passed()},
          {"simulated_ps", r.simulated.count()},
          {"events", r.events},
          {"frames_decoded", r.frames_decoded},
          {"frames_clean", r.frames_clean},
          {"frames", scenarios::wire_frames_json(r.frames)},
          {"frames_not_kept", r.frames_decoded - r.frames.size()},
          {"positions", reported_json(r.positions)},
          {"parameters", reported_json(r.parameters)},
          {"notes", r.notes},
          {"events_not_acted", scenarios::events_not_acted_json(r.events_not_acted)},
          {"frame_cut_by_end", r.frame_cut_by_end ? json(cut_frame_json(r)) : json(nullptr)},
          {"violations", scenarios::violations_json(r.violations)},
          {"verdict", scenarios::verdict_json(r.conclusion)},
          {"conformance", scenarios::conformance_json(r.conformance)},
          {"expectations", expectations}};
  if (!r.incomplete.empty()) {
    j["incomplete"] = r.incomplete;
    if (r.interrupted != 0) j["interrupted"] = scenarios::signal_name(r.interrupted);
  }
  return j;
}

std::string junit_xml(const BenchResult& r) {
  using scenarios::xml_escape;
  std::size_t failures = 0, errors = 0;
  std::string cases;
  for (const auto& e : r.expectations) {
    // A run that ended early is an error of the run, not a failed expectation of the master.
    const bool error = !e.passed && e.name == "complete";
    (error ? errors : failures) += e.passed ? 0 : 1;
    const std::string type = error ? "error type=\"incomplete\"" : "failure type=\"expectation\"";
    cases += testcase(e.name, r.file, e.passed ? "" : "      <" + type + " message=\"" + xml_escape(e.detail) + "\"/>\n");
  }
  const std::string tests = std::to_string(r.expectations.size());
  const std::string counts = "\" failures=\"" + std::to_string(failures) + "\" errors=\"" + std::to_string(errors) + "\"";
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"endatsim cosim\" tests=\"" + tests + counts +
         ">\n  <testsuite name=\"" + xml_escape(r.name) + "\" tests=\"" + tests + counts + " skipped=\"0\">\n" + cases +
         "  </testsuite>\n</testsuites>\n";
}

int report(const BenchResult& r, const OutputPaths& outputs, bool verbose, std::ostream& out, std::ostream& err) {
  write_summary(out, r, verbose);
  out.flush();
  try {
    if (outputs.json) scenarios::write_file(*outputs.json, scenarios::json_file_text(to_json(r)));
    if (outputs.junit) scenarios::write_file(*outputs.junit, junit_xml(r));
    if (outputs.log) {
      std::string log;
      for (const auto& f : r.frames) log += scenarios::frame_log_line(f);
      scenarios::write_file(*outputs.log, log);
    }
  } catch (const std::exception& e) {
    err << "endatsim: " << e.what() << std::endl;
    return exit_status::kBadInput;
  }
  if (r.interrupted != 0) return exit_status::interrupted(r.interrupted);
  if (!r.incomplete.empty()) return exit_status::kIncomplete;
  return r.passed() ? exit_status::kPass : exit_status::kFail;
}

void check_outputs(const std::string& bench, const OutputPaths& outputs, const std::optional<std::string>& vcd,
                   const std::string& prefix) {
  std::vector<scenarios::OutputPath> paths;
  for (const auto& [name, path] : {std::pair{"json", &outputs.json}, {"junit", &outputs.junit}, {"log", &outputs.log}, {"vcd", &vcd}})
    if (*path) paths.push_back({prefix + name, **path});
  scenarios::check_output_paths({bench}, "the bench file", paths);
}

}  // namespace endatsim::cosim

#pragma once

#include <nlohmann/json.hpp>
#include <ostream>

#include "endatsim/scenarios/json_tokens.hpp"
#include "endatsim/scenarios/runner.hpp"

namespace endatsim::scenarios {

// A readable summary: frames, positions, CRC errors, measured t_D, violations with time,
// value, limit and spec section, and each expectation's verdict.
void write_summary(std::ostream& out, const ScenarioResult& r, bool verbose);

// The violations grouped by check, each with its count from the conformance table (which counts
// the findings not kept too), the first three of each (all kept with `verbose`).
void write_violations(std::ostream& out, const std::vector<checker::Violation>& violations,
                      const std::vector<checker::RowConformance>& rows, bool verbose);

// The violations as the stable JSON format has them; the two verdicts (spec envelope, this encoder).
nlohmann::json violations_json(const std::vector<checker::Violation>& violations);
// The events a run ended before: a warning line each (the first three) and a JSON list.
void write_events_not_acted(std::ostream& out, const std::vector<EventNotActed>& events);
nlohmann::json events_not_acted_json(const std::vector<EventNotActed>& events);
nlohmann::json verdict_json(const checker::Conclusion& conclusion);
// "verdict: conforms to this encoder; outside the spec envelope: ..."; the violations name the
// envelope-only findings.
void write_verdict(std::ostream& out, const checker::Conclusion& conclusion,
                   const std::vector<checker::Violation>& violations);

// One line per row that a named option loosened in this run (every report says so).
void write_relaxations(std::ostream& out, const std::vector<checker::RowConformance>& rows);

// The conformance table: each row judged (how often, violations, warnings) or why not.
void write_conformance(std::ostream& out, const std::vector<checker::RowConformance>& rows);
nlohmann::json conformance_json(const std::vector<checker::RowConformance>& rows);

// The stable result format (documented in docs/command-line.md and schema/results.schema.json),
// with the frames the result kept.
nlohmann::json to_json(const ScenarioResult& r);
// Its parts: one frame, and everything but the frames (the results file streams them). The
// frame's tokens are what the results file writes; frame_json() is the same frame as a tree.
JsonTokens frame_tokens(const ScenarioResult& r, const master::FrameResult& f);
nlohmann::json frame_json(const ScenarioResult& r, const master::FrameResult& f);
nlohmann::json result_json_without_frames(const ScenarioResult& r);

}  // namespace endatsim::scenarios

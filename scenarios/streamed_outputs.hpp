// The outputs of `endatsim run` written while the runs go (RunSink, run_recorder.hpp): the
// transaction log as text or JSON lines, and the results file. Each holds one frame at a time,
// so a run of millions of frames writes them with the memory of a few.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "endatsim/scenarios/junit.hpp"
#include "endatsim/scenarios/run_recorder.hpp"
#include "endatsim/scenarios/runner.hpp"

namespace endatsim::scenarios {

// The decoded transaction log (transaction_log.hpp), a record per frame as it is settled.
// Text: "# NAME (FILE, seed N)", the rows an option relaxed, a line per frame, then "# N
// frames". JSON lines: one record per line, each naming its scenario.
class TransactionLogWriter final : public RunSink {
 public:
  enum class Format : std::uint8_t { Text, JsonLines };
  TransactionLogWriter(std::ostream& out, Format format) : out_(out), format_(format) {}
  void begin(const ScenarioResult& header) override;
  void frame(const ScenarioResult& header, const master::FrameResult& frame,
             std::span<const checker::Violation> findings) override;
  void end(const ScenarioResult& result) override;
  // The text log's last lines for a run that ended early: why, then each file not run.
  static void write_incomplete(std::ostream& out, const std::string& incomplete, const std::vector<NotRun>& not_run);
  // The same as the last JSON line: {"incomplete": why, "not_run": [{"file", "reason"}...]}, so
  // that a log cut short by a limit or a signal never reads as a whole run.
  static void write_incomplete_json(std::ostream& out, const std::string& incomplete, const std::vector<NotRun>& not_run);

 private:
  std::ostream& out_;
  Format format_;
  std::string line_;  // a JSON line as it is written
};

// The results file (docs/command-line.md, schema/results.schema.json): {"endatsim": VERSION,
// "scenarios": [...], then "passed" and, for a run that ended early, "complete", "incomplete"
// and "not_run"}. Each scenario's object holds "name", "file", "seed", then "frames" as they
// come, then the rest of the result in key order.
class ResultsJsonWriter final : public RunSink {
 public:
  ResultsJsonWriter(std::ostream& out, const std::string& version);
  void begin(const ScenarioResult& header) override;
  void frame(const ScenarioResult& header, const master::FrameResult& frame,
             std::span<const checker::Violation> findings) override;
  void end(const ScenarioResult& result) override;
  // A scenario's object as another writer wrote it (`endatsim merge`): `object` writes it from
  // its opening "    {" to its closing "    }", without the comma or newline after.
  void copy_scenario(const std::function<void(std::ostream&)>& object);
  // Closes the document: whether every scenario passed, and why the run is incomplete ("" if
  // it is not) with the files not run; a shard's partial (`run --shard`) also gets "shard".
  void finish(bool passed, const std::string& incomplete, const std::vector<std::string>& not_run,
              const nlohmann::json* shard = nullptr);

 private:
  std::ostream& out_;
  std::size_t scenarios_ = 0;
  std::size_t frames_ = 0;  // of the current scenario
};

// A result's object as ResultsJsonWriter writes it, frames from the result's list.
void write_result_json(std::ostream& out, const ScenarioResult& r);

}  // namespace endatsim::scenarios

// The decoded transaction log: each frame the master ran as one record, like the command
// sequence a protocol analyser or the EnDat Demotool records — time, mode command, what was
// sent, what came back, whether the CRC held, additional data, the outcome and the violations
// the checker attributed to the frame. A record is data: "sent", "received" and "additional"
// are name -> value objects, so a new field appears in the text and in the JSON lines by
// being added in one place (transaction_tokens in transaction_log.cpp).
#pragma once

#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "endatsim/checker/timing_checker.hpp"
#include "endatsim/master/master.hpp"
#include "endatsim/scenarios/json_tokens.hpp"
#include "endatsim/scenarios/runner.hpp"

namespace endatsim::scenarios {

// One frame (or one continuous-clock word) as a record:
// {"time_ps", "time", "frame", "word", "command", "mode_bits", "sent": {...}, "received": {...},
//  "crc_ok": bool|null, "additional": {...}, "outcome", "violations": [{"check", "severity",
//  "field", "message"}]}, and "scenario" last when one is named. The tokens are what the log
// writes; transaction_of() is the same record as a tree.
JsonTokens transaction_tokens(const master::FrameResult& frame, std::span<const checker::Violation> violations,
                              const std::string* scenario = nullptr);
nlohmann::ordered_json transaction_of(const master::FrameResult& frame, std::span<const checker::Violation> violations);

// Records of every frame in order.
std::vector<nlohmann::ordered_json> transactions(const std::vector<master::FrameResult>& frames,
                                                 const std::vector<checker::Violation>& violations);

// One line per record, columns aligned for reading.
std::string transaction_line(const JsonTokens& record);
// The log of the frames a result kept (all, unless RunOptions::kept said fewer), as
// TransactionLogWriter (streamed_outputs.hpp) writes it while a run goes: "# NAME (FILE, seed
// N)", a line per frame, "# N frames"; JSON lines: one compact object per line.
std::string transaction_log_text(const ScenarioResult& r);
std::string transaction_log_jsonl(const ScenarioResult& r);

// For testbenches that embed the models: attach to a master (add_observer) to collect the
// frames as they end; format them with the checker's violations afterwards.
class TransactionRecorder final : public master::MasterObserver {
 public:
  void on_frame_start(const master::FrameResult&) override {}
  void on_sample(const master::FrameResult&, unsigned, bool, bool) override {}
  bool wants_samples() const override { return false; }
  void on_frame_end(const master::FrameResult& frame) override { frames_.push_back(frame); }
  const std::vector<master::FrameResult>& frames() const { return frames_; }

 private:
  std::vector<master::FrameResult> frames_;
};

}  // namespace endatsim::scenarios

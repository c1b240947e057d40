#pragma once

#include <atomic>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "endatsim/scenarios/frame_replay.hpp"
#include "endatsim/scenarios/limits.hpp"
#include "endatsim/scenarios/run_recorder.hpp"
#include "endatsim/scenarios/scenario.hpp"

namespace endatsim::scenarios {

// How far a run has come, for a progress line drawn by another thread: updated every few
// thousand kernel events.
struct RunProgress {
  std::atomic<std::int64_t> simulated_ps{0};
  std::atomic<std::int64_t> end_ps{0};  // where the run stops at the latest (max_time and --max-time)
  std::atomic<std::uint64_t> frames{0};
};

struct RunOptions {
  std::optional<std::string> vcd_path;
  std::optional<std::uint64_t> seed;  // overrides the scenario's seed
  Limits limits;                      // what the run may cost (see limits.hpp)
  RunProgress* progress = nullptr;    // when set, kept up to date while the run runs
  // The VCD also gets a text trace, endat.decoded, with each frame's mode command from its FE1
  // and what the master decoded from its end: for GTKWave (sigrok skips text traces).
  bool vcd_decoded = false;
  // What the result keeps in memory: the first `kept` frames, the last `kept` to 2 x `kept`
  // encoder frames and the first `kept` findings of each check (every one is counted). All of
  // them by default; a long run keeps a few and streams the rest to `sinks`.
  std::size_t kept = SIZE_MAX;
  std::vector<RunSink*> sinks;  // outputs written while the run goes (run_recorder.hpp)
  // Frames that repeat are played from a recording (frame_replay.hpp), with the same results.
  Engine engine = Engine::Auto;
};

struct ExpectationResult {
  std::string name;
  bool passed = false;
  std::string detail;
};

// Every good read against the position the encoder latched at its first falling edge (the
// positions_match_encoder expectation). No good read at all does not match.
struct PositionComparison {
  bool match = false;
  std::string detail;
};

struct ScenarioResult {
  std::string file;
  std::string name;
  std::string description;
  std::optional<FieldNote> field;
  std::uint64_t seed = 0;
  Time simulated{0};
  std::uint64_t events = 0;
  std::uint64_t frames_replayed = 0;  // frames played from a recording (frame_replay.hpp); in no output
  std::vector<EventNotActed> events_not_acted;  // the scenario's events that the run ended before
  bool finished = false;  // the script ran to its end within max_time
  // Not empty when the run was ended early, by a limit of limits.hpp or an interruption: why,
  // where and how to change it. Such a result is incomplete and does not pass.
  std::string incomplete;
  int interrupted = 0;  // the signal that ended it (interrupt.hpp), or 0
  Time true_round_trip{0};
  sim::Hertz f_c = 0;
  unsigned position_bits = 0;
  unsigned multiturn_bits = 0;  // > 0: positions split into revolutions (upper bits) and singleturn
  // Every frame counted; the first RunOptions::kept frames kept (all by default).
  FrameTally tally;
  std::vector<master::FrameResult> frames;
  std::vector<master::DelayMeasurementResult> measurements;  // the first RunOptions::kept
  std::uint64_t measurements_count = 0;                       // every one that ran
  std::optional<master::DelayMeasurementResult> last_measurement;
  std::vector<slave::EncoderFrame> encoder_frames;  // the last ones kept
  std::vector<checker::Violation> violations;        // the first RunOptions::kept of each check
  checker::Conclusion conclusion;                    // the verdicts over every finding, kept or not
  std::vector<checker::RowConformance> conformance;  // every row of the timing table, with its counts
  // What the expectations need of the frames, gathered as they end.
  std::optional<PositionComparison> positions_match;  // every good read against the encoder (expectation, sweeps)
  std::vector<std::uint64_t> positions_read;          // with positions expected: as many, and one more
  std::uint64_t positions_read_count = 0;
  std::map<std::size_t, master::FrameResult> operation_frames;  // the last of each operation with an expect
  std::uint64_t late_findings = 0;  // findings for a frame already written out (a checker bug; 0)
  std::uint64_t cycle_overruns = 0;    // frames that started later than their read cycle said
  std::uint64_t busy_timeouts = 0;     // await_not_busy operations that gave up
  std::uint64_t busy_unreadable = 0;   // await_not_busy whose polls carried no additional data 1
  slave::MemoryImage encoder_memory;   // at the end of the run
  std::vector<slave::MemoryImage> bus_memory;  // of the further encoders on the bus
  std::vector<std::vector<slave::EncoderFrame>> bus_frames;
  master::StartupInfo startup;
  std::optional<master::ChecksumCheck> checksum;
  std::uint64_t retries = 0;
  std::uint64_t remeasurements = 0;
  master::SafetyReport safety;
  std::optional<master::DiagnosisReport> diagnosis;  // with the master's diagnostics enabled
  // Ground truth against the safety functions: good reads while the encoder had an error, and
  // whether the released position is what the encoder measured.
  std::uint64_t undetected_errors = 0;
  std::optional<bool> release_position_correct;
  std::vector<ExpectationResult> expectations;
  bool passed() const;
};

// Over the frames and encoder frames a result kept (all of them, by default).
PositionComparison compare_positions_with_encoder(const Scenario& scenario, const ScenarioResult& r);

// expect.violations against the findings: each listed check as often as it says; any other
// check never (its findings as a count), or, with "*" (kAnyOtherCheck) listed, all the others
// together as often as "*" says. `counts`: findings per check, kept or not (finding_counts).
void judge_violations(const Expectations& expect, std::map<std::string, std::uint64_t> counts,
                      std::vector<ExpectationResult>& out);
void judge_violations(const Expectations& expect, const std::vector<checker::Violation>& violations,
                      std::vector<ExpectationResult>& out);
// Findings per check from the conformance table, which counts every one.
std::map<std::string, std::uint64_t> finding_counts(const std::vector<checker::RowConformance>& rows);

// Runs the scenario to the end of its script and judges its expectations. Throws ScenarioError
// before running when the scenario exceeds options.limits (resolve_limits).
ScenarioResult run_scenario(const Scenario& scenario, const RunOptions& options = {});

}  // namespace endatsim::scenarios

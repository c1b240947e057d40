// What one run may cost. Scenario files come from field reports and other people's tools, so
// every run is bounded: simulated time (the scenario's max_time), kernel events, the frames the
// script asks for, the entries of the events list, and the records kept for the results. Each
// limit has a default far above what any bundled, field or safety scenario needs, a scenario key
// (limits.*) and a command-line option (--max-*); the smaller of the two applies, and a scenario
// may not ask for more than the command line (or the default) grants.
// What a file shows is refused before the run (ScenarioError: file, JSON path, the limit); what
// shows only while running ends the run early, its result marked incomplete.
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

#include "endatsim/input/text.hpp"
#include "endatsim/sim/time.hpp"

namespace endatsim::scenarios {

struct Scenario;

struct Limits {
  static constexpr std::uint64_t kDefaultKernelEvents = 20'000'000;
  static constexpr std::uint64_t kDefaultScriptFrames = 100'000;
  static constexpr std::uint64_t kDefaultEvents = 1'000;
  static constexpr std::uint64_t kDefaultRecords = 50'000;

  std::optional<sim::Time> max_time;                 // none: the scenario's max_time
  std::uint64_t kernel_events = kDefaultKernelEvents;  // events the simulation kernel runs
  std::uint64_t script_frames = kDefaultScriptFrames;  // frames and polls the script asks for
  std::uint64_t events = kDefaultEvents;               // entries of the scenario's events list
  std::uint64_t records = kDefaultRecords;  // frames (master's and encoders'), measurements and violations kept
};

// A run that a limit ended early where no incomplete result can stand in (a diagram).
class LimitReached : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// What a scenario file sets under "limits" (each optional).
struct ScenarioLimits {
  std::optional<std::uint64_t> kernel_events, script_frames, events, records;
};

// The frames and polls a script asks for: per entry count x (1 + continuous_words) for frames,
// max_polls for await_not_busy, 1 for any other operation (saturating, never wrapping).
std::uint64_t script_frames(const Scenario& scenario);

// The limits a run of `scenario` gets under `granted` (the command line's or the defaults):
// each the smaller of the two. Throws ScenarioError naming the file, the JSON path and the limit
// when the scenario asks for more than granted, or when its script or events list exceed them.
Limits resolve_limits(const Scenario& scenario, const Limits& granted);

// The command-line option and the scenario key of each limit, for messages.
inline constexpr const char* kKernelEventsOption = "--max-kernel-events";
inline constexpr const char* kScriptFramesOption = "--max-script-frames";
inline constexpr const char* kEventsOption = "--max-events";
inline constexpr const char* kRecordsOption = "--max-records";
inline constexpr const char* kMaxTimeOption = "--max-time";

// Sets one limit from text, as the command line and the co-simulation bridge give it: `name` is
// "max-time" (a duration above 0) or "max-kernel-events", "max-script-frames", "max-events",
// "max-records" (an integer 1 .. 2^64 - 1). Throws std::invalid_argument naming the option and
// what it expects; an unknown name is a std::logic_error.
void set_limit(Limits& limits, const std::string& name, const std::string& text);
// The names set_limit takes.
inline constexpr const char* kLimitNames[] = {"max-time", "max-kernel-events", "max-script-frames", "max-events",
                                              "max-records"};

using input::trimmed;

}  // namespace endatsim::scenarios

#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "endatsim/checker/timing_checker.hpp"
#include "endatsim/line/line.hpp"
#include "endatsim/master/master.hpp"
#include "endatsim/scenarios/limits.hpp"
#include "endatsim/slave/encoder.hpp"

namespace endatsim::scenarios {

using sim::Time;

// "3", ">=1", "<=2", "2..5": how many times something must happen.
// The key of expect.violations that counts every check the others do not name, together.
inline constexpr std::string_view kAnyOtherCheck = "*";

struct CountMatcher {
  std::uint64_t min = 0;
  std::uint64_t max = UINT64_MAX;
  std::string text;
  bool matches(std::uint64_t n) const { return n >= min && n <= max; }
};

struct DelayExpectation {
  std::optional<bool> accepted;
  std::optional<Time> max_error;   // |measured t_D - true round trip|
  bool max_error_is_eighth = false;  // "T/8": an eighth of the period at the master's f_c
};

// What the last frame of one operation must show (an "expect" inside a script entry).
struct AdditionalDataExpectation {
  protocol::Information information = protocol::Information::Nop1;
  std::optional<std::uint16_t> data;
  std::optional<bool> busy;
  std::optional<bool> rm;  // 2.3.4.3: reference mark crossed (incremental encoders)
};

struct FrameExpectation {
  std::optional<std::string> outcome;           // master::to_string(FrameOutcome)
  std::optional<std::uint64_t> position;
  std::optional<bool> error1;
  std::optional<std::uint8_t> echo_address;     // parameter frames
  std::optional<std::uint16_t> echo_parameter;  // parameter frames: the parameter written or read
  std::optional<std::uint64_t> test_value;
  std::optional<std::vector<AdditionalDataExpectation>> additional_data;  // in wire order
};

// A word of the encoder's memory at the end of the run (ground truth, not what the master read).
struct MemoryExpectation {
  std::size_t encoder = 0;  // 0: "encoder"; k: the k-th of "bus"
  protocol::MemoryArea area = protocol::MemoryArea::OperatingStatus;
  std::uint8_t block = 0;
  std::uint8_t address = 0;
  std::uint16_t value = 0;
};

// What the start-up routine (docs/model.md §8) must have read.
struct StartupExpectation {
  std::optional<bool> completed;
  std::optional<std::uint16_t> errors, warnings, word13, word37;
};

// What the master's safety functions must have found and decided. Functions not listed in
// `findings` must have found nothing.
struct SafetyExpectation {
  std::map<std::string, CountMatcher> findings;  // by master::to_string(SafetyFunction)
  std::optional<bool> axis_released;
  std::optional<bool> release_position_correct;  // the released value is what the encoder measured
  std::optional<CountMatcher> undetected_errors;  // frames read as good while the encoder had an error
  std::optional<CountMatcher> position_comparisons;
};

// What the master's diagnosis must have collected. Note kinds not listed in `notes`
// must not have occurred; values are the last ones read.
struct DiagnosisExpectation {
  std::map<std::string, CountMatcher> notes;                // by master::to_string(DiagnosisNoteKind)
  std::map<unsigned, unsigned> valuation_numbers;           // by A3 address (valuation number n: address n)
  std::optional<std::uint16_t> temperature1, temperature2;  // 0.1 K
  std::map<unsigned, std::uint16_t> additional_sensors;     // by address, 0.1 K
  std::optional<std::uint16_t> configuration;               // operating parameters word 3 in force
  std::optional<std::uint16_t> warnings;                    // word 1 as last read
  std::optional<CountMatcher> ignored_addresses;
};

struct Expectations {
  std::map<std::string, CountMatcher> outcomes;    // non-measurement frames by master::FrameOutcome
  std::optional<bool> positions_match_encoder;
  std::optional<std::vector<std::uint64_t>> positions;
  std::optional<DelayExpectation> delay_measurement;
  std::map<std::string, CountMatcher> violations;  // checks not listed must not occur
  std::optional<std::uint64_t> max_cycle_overruns;
  std::vector<MemoryExpectation> memory;
  std::optional<std::uint64_t> max_busy_timeouts;
  std::optional<CountMatcher> busy_timeouts;  // await_not_busy operations that gave up
  std::optional<bool> checksum_ok;            // the last verify_checksum (3.5.26)
  std::optional<CountMatcher> retries;        // frames the careful master repeated
  std::optional<CountMatcher> remeasurements; // delay measurements the careful master added
  std::optional<StartupExpectation> startup;
  std::optional<SafetyExpectation> safety;
  std::optional<DiagnosisExpectation> diagnosis;
};

// Something that happens while the script runs: a change of the line or a fault of
// line or encoder. It happens at a time, or at frame k (the master's FE1 of its k-th frame,
// delay-measurement frames included, counted from 0), optionally at the n-th rising CLOCK
// edge of that frame at `end`'s pins, plus `offset`.
struct Event {
  enum class Kind : std::uint8_t {
    SetCable, BitFlip, Glitch, Stuck, RandomBitErrors, LateDriverRelease, LossOfFailsafe,  // line
    ErrorSources, MemoryAccessTime, TCal, PowerInterruption, CorruptWord, ProbeTrigger,    // encoder
    StuckErrorMessages, Slip, Position2Fault, SensorValues,                                // encoder (safety, diagnosis)
  };
  Kind kind = Kind::SetCable;
  std::optional<Time> at;
  std::optional<std::uint64_t> frame;
  unsigned clock = 0;  // 0: at FE1 of the frame
  Time offset{0};
  // set_cable
  double cable_length_m = 0;
  Time cable_delay_per_m{0};
  // line faults
  line::Wire wire = line::Wire::Data;
  line::ObservationPoint end = line::ObservationPoint::MasterPins;
  Time width{0};                  // bit_flip: one period of the master's f_c unless given
  unsigned level = 0;             // stuck, loss_of_failsafe: 0 or 1
  std::optional<Time> duration;   // stuck, random_bit_errors: none = to the end; power_interruption, probe_trigger
  double rate = 0;                // random_bit_errors: probability per clock period
  // encoder faults
  std::uint16_t errors = 0, warnings = 0;
  Time t_ac_read{0}, t_ac_write{0}, t_cal{0};
  slave::Selection selection;
  std::uint8_t address = 0;
  std::uint16_t xor_mask = 0;
  bool error_message_1_stuck = false, error_message_2_stuck = false;  // stuck_error_messages
  std::int64_t steps = 0;                                             // slip, position2_fault
  slave::SensorValues sensors;                                        // sensors
};

// An event the run ended before: its place in the scenario's list, its kind ("slip") and when it
// was to act ("at 5 ms", "frame 500", "frame 500, clock 9").
struct EventNotActed {
  std::size_t index = 0;
  std::string kind;
  std::string when;
  bool operator==(const EventNotActed&) const = default;
};

inline Event cable_change(Time at, double length_m, Time delay_per_m) {
  Event e;
  e.at = at;
  e.cable_length_m = length_m;
  e.cable_delay_per_m = delay_per_m;
  return e;
}

// The header of a field-bug scenario (scenarios/field/): what went wrong in the field, why,
// which spec rule is involved and what the scenario asserts.
struct FieldNote {
  std::string symptom, cause, spec, asserts;
};

struct Scenario {
  std::string file;
  std::string name;
  std::string description;
  std::optional<FieldNote> field;
  std::uint64_t seed = 1;
  // The longest simulated time a scenario may name: max_time, an operation's or event's `at`,
  // durations and cycles.
  static constexpr Time kMaxTime = sim::ms(60'000);
  Time max_time = sim::ms(1000);
  ScenarioLimits limits;  // what the file asks for; resolve_limits gives a run's limits
  line::LineParams line;
  slave::EncoderParams encoder;
  std::vector<slave::EncoderParams> bus;  // further encoders on the same DATA/CLOCK bus (2.10)
  master::MasterParams master;
  checker::CheckerParams checker;
  std::vector<master::Operation> script;
  std::vector<std::optional<FrameExpectation>> operation_expectations;  // one per script entry
  std::vector<Event> events;
  Expectations expect;
};

}  // namespace endatsim::scenarios

// master/safety.hpp — what subsequent electronics for safety-oriented designs do beyond reading
// positions (the English EnDat 2.2 brochure's "Safety Techniques"; spec 1, 2.3.1, 3.5.3, 3.5.19,
// 3.5.26, 3.9.11, 3.9.20, 3.9.24, 3.9.37). Each function can be switched off, so that a scenario
// shows what a master without it misses; what a function catches is a SafetyFinding.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "endatsim/protocol/indexed_table.hpp"
#include "endatsim/master/frame_result.hpp"
#include "endatsim/master/master_function.hpp"
#include "endatsim/master/operation.hpp"
#include "endatsim/protocol/protocol.hpp"
#include "endatsim/sim/parameter.hpp"
#include "endatsim/sim/time.hpp"

namespace endatsim::master {

struct CrcCheck;

using sim::Time;

enum class SafetyFunction : std::uint8_t {
  ErrorMessages,          // F1 and F2 evaluated separately (2.3.1: two independent error messages)
  PositionValue2,         // position value 2 compared with position value 1 (3.9.11, 3.9.20, 3.9.24)
  ForcedDynamicSampling,  // error messages forced and verified (3.5.3)
  CrcSelfTest,            // the master's own CRC evaluation fed with sequences of known result
  StartupPositions,       // multiple transmission of the position value at start-up
  Checksums,              // words 47 (3.5.26) and 63 (3.9.37)
  Acknowledgements,       // what the encoder acknowledges equals what was written (2.6, 2.6.1)
  FollowingError,         // servo lag against the commanded motion
  CommandSet,             // word 37 read at start-up: no communication command (2.3, 3.5.22)
};
inline constexpr std::array kSafetyFunctions{
    SafetyFunction::ErrorMessages,    SafetyFunction::PositionValue2, SafetyFunction::ForcedDynamicSampling,
    SafetyFunction::CrcSelfTest,      SafetyFunction::StartupPositions, SafetyFunction::Checksums,
    SafetyFunction::Acknowledgements, SafetyFunction::FollowingError, SafetyFunction::CommandSet};
static_assert(protocol::lists_in_order(kSafetyFunctions, SafetyFunction::CommandSet),
              "kSafetyFunctions: every safety function in the order of its value, up to the last one, CommandSet (names and "
              "expectations follow it); a new function goes after it, in the list and in this check");
std::string_view to_string(SafetyFunction f);  // "error_messages", ...

// The motion the drive commands: the set-point the following error is measured against.
struct MotionSetpoint {
  std::uint64_t start = 0;
  std::int64_t counts_per_s = 0;
  std::uint64_t at(Time t, unsigned position_bits) const;
};

struct SafetyParams {
  bool error_messages = false;
  bool read_error_sources = true;  // with error_messages: read word 0 when an error message appears (3.4.1)
  bool position_value_2 = false;
  bool forced_dynamic_sampling = false;
  // 3.5.3: port addresses that force error message 1 / 2 (the table lost a column; docs/model-reference.md).
  std::uint8_t forced_error1_port = protocol::parameters::kForcedError1FirstPort;
  std::uint8_t forced_error2_port = protocol::parameters::kForcedError2FirstPort;
  Time forced_sampling_deadline = sim::ms(1);  // 3.5.3: "with one of the next EnDat 2.2 queries (< 1 ms)"
  bool crc_self_test = false;
  bool startup_positions = false;
  unsigned startup_repetitions = 3;        // consecutive values that must agree before release
  unsigned startup_max_reads = 20;         // then the axis stays blocked
  std::uint64_t startup_tolerance = 1;     // LSB two consecutive values may differ by, beyond the set-point's motion
  bool checksums = false;
  bool acknowledgements = false;
  bool following_error = false;
  // 2.3: "Encoders supporting the mode command 'Encoder receive communication command' must not
  // be used for safety-oriented applications": the start-up reads word 37 (3.5.22) and keeps the
  // axis blocked when it declares that command, or cannot be read.
  bool command_set = false;
  std::uint64_t following_error_limit = 1000;  // LSB
  MotionSetpoint setpoint;

  bool enabled(SafetyFunction f) const;
  // Throws std::invalid_argument naming the parameter and its limit.
  void validate() const;
};

// The scalar keys of "master.safety", one row each (sim/parameter.hpp).
std::span<const sim::Parameter<SafetyParams>> safety_parameters();

struct SafetyFinding {
  SafetyFunction function = SafetyFunction::ErrorMessages;
  Time at{0};
  std::optional<std::uint64_t> frame;
  std::string message;
};

// The accuracy of position value 2 against position value 1 as the encoder states it: velocity
// ranges with their accuracy (3.5.19 words 33/34, or 3.9.11 words 11..14 of the 2.2 area when
// those hold 65535), the offset (3.9.24), the direction (3.9.13) and the bits compared (3.9.20).
struct Position2Parameters {
  bool linear = false;
  std::uint32_t measuring_steps = 0;  // 3.5.12 words 20/21: nm (linear) or steps per revolution
  std::uint16_t max_velocity = 0;     // 3.5.18 word 32: m/min or rpm
  struct Range {
    std::uint32_t conversion_factor = 0;  // c_i: the range ends at max_velocity / c_i
    std::uint32_t accuracy = 0;           // a_i in LSB
  };
  std::vector<Range> ranges;
  bool reversed = false;        // word 16 of the 2.2 area, bit 0
  unsigned comparison_bits = 0;  // word 26; 0: all bits
  std::int64_t offset = 0;       // words 31..33, 48-bit two's complement
  // The accuracy at this velocity (measuring steps per second); none above the last range.
  std::optional<std::uint32_t> accuracy_at(double steps_per_s) const;
};
// From the 48 words of the encoder manufacturer (2.1) and the 64 of the 2.2 area (3.9).
Position2Parameters position2_parameters(const std::vector<std::uint16_t>& manufacturer,
                                         const std::vector<std::uint16_t>& endat22);

// What the safety functions found and decided; the diagnosis the master collected.
struct SafetyReport {
  std::vector<SafetyFinding> findings;
  bool axis_released = false;
  Time released_at{0};
  std::optional<std::uint64_t> release_frame;
  std::uint64_t release_position = 0;
  unsigned startup_reads = 0;
  std::uint64_t position_comparisons = 0;      // position value 2 against position value 1
  std::uint64_t comparisons_out_of_range = 0;  // velocity above every range: nothing to compare with
  std::optional<std::uint16_t> error_sources;  // word 0 as read after an error message (3.4.1)
  std::optional<std::uint16_t> operating_status_error_sources;  // additional data 2 (2.3.5.3)
  std::optional<std::uint16_t> checksum47_stored, checksum47_computed, checksum63_stored, checksum63_computed;
  std::size_t count(SafetyFunction f) const;
};

// The safety functions' checks of every frame: error messages 1 and 2 (2.3.1), forced dynamic
// sampling as the start-up forces it (3.5.3), the command set (2.3, 3.5.22), the acknowledgment
// of writes (2.6, 2.6.1), the following error and the comparison of position value 2 (3.9.11,
// 3.9.20, 3.9.24). It keeps the report and says when word 0 is due to be read; the master
// schedules the frames and runs the start-up's own steps (CRC self-test, checksums, release).
class SafetyMonitor {
 public:
  explicit SafetyMonitor(const SafetyParams& params) : params_(params) {}

  SafetyReport& report() { return report_; }
  const SafetyReport& report() const { return report_; }
  // A frame ended; `purpose` is its operation's, `position_bits` what the master clocks. Sets
  // f.error_detected: what the master made of F1 and F2.
  void on_frame(FrameResult& f, Operation::Purpose purpose, unsigned position_bits);
  void find(SafetyFunction function, const FrameResult& f, std::string message);
  void find(SafetyFunction function, Time now, std::string message);  // not tied to a frame
  // 3.4.1: word 0 is to be read (an error message appeared).
  bool error_sources_due() const { return error_sources_due_; }
  void clear_error_sources_due() { error_sources_due_ = false; }
  // The start-up's own checks: the CRC evaluation against sequences of known result (`crc` the
  // master's, at its width), and the repeated position reads, which release the axis (true once
  // enough agree; `last_read`: the last the master makes).
  void run_crc_self_test(const CrcCheck& crc, unsigned position_bits, Time now);
  void begin_startup_positions();
  bool startup_position_read(const FrameResult& f, unsigned position_bits, bool last_read);
  // What the comparison of position value 2 needs, once the start-up has read it.
  void set_position2_parameters(const Position2Parameters& p) { position2_parameters_ = p; }

 private:
  void check_error_messages(FrameResult& f);
  void check_command_set(const FrameResult& f);
  void check_forced_sampling(const FrameResult& f);
  void check_following_error(const FrameResult& f);
  void check_acknowledgement(const FrameResult& f);
  void check_position_value_2(const FrameResult& f);

  const SafetyParams& params_;
  SafetyReport report_;
  Operation::Purpose purpose_ = Operation::Purpose::None;  // of the frame being judged
  unsigned position_bits_ = 0;
  bool error_sources_due_ = false;
  unsigned startup_agreeing_ = 0;
  std::uint64_t startup_previous_ = 0;
  Time startup_previous_at_{0};
  bool error_state_ = false, disagree_state_ = false, lag_state_ = false;
  std::optional<Time> forced_sent_at_;
  bool forcing_ = false;
  std::optional<std::pair<std::uint64_t, Time>> last_good_;  // position and FE1 of the last good read (velocity)
  struct Position2Read {
    std::uint64_t position1 = 0;
    Time at{0};
    std::uint64_t frame = 0;
    double velocity = 0;
    std::uint64_t value = 0;
    unsigned words = 0;
  };
  std::optional<Position2Read> position2_;
  std::optional<Position2Parameters> position2_parameters_;
  struct Written {
    std::uint8_t address = 0;
    std::uint16_t value = 0;
  };
  std::optional<Written> acknowledgement_due_;
};

// The safety functions on top of the master's scheduler (master_function.hpp): the start-up a
// SafetyStartup operation asks for (the master's CRC self-test, the command set, the checksums,
// forced dynamic sampling, the position reads that release the axis; planned here, the frames
// run by the scheduler) and the checks of every frame (SafetyMonitor).
class SafetyFunctions final : public MasterFunction {
 public:
  explicit SafetyFunctions(const SafetyParams& params) : params_(params), monitor_(params) {}

  const SafetyReport& report() const { return monitor_.report(); }

  Planned plan(const FunctionContext& ctx, Sequence& plan) override;
  void endat22_area_read(const FunctionContext& ctx, bool complete) override;
  void on_frame(FrameResult& f, const FunctionContext& ctx) override;
  bool ends_operation(const FrameResult& f, const FunctionContext& ctx, bool last) override;
  std::optional<StatusRead> status_read_due() const override;
  void status_read_planned() override { monitor_.clear_error_sources_due(); }

 private:
  void plan_startup(const FunctionContext& ctx, Sequence& plan);

  const SafetyParams& params_;
  SafetyMonitor monitor_;
};

// The bit sequences of known result the CRC self-test feeds to the master's CRC evaluation: the
// spec's examples (A4) and vectors for other widths (docs/model.md §12). A manufacturer keeps such
// a table; here it is data.
struct CrcVector {
  unsigned bits;
  bool error1, error2, endat22;
  std::uint64_t position;
  std::uint8_t crc;
};
std::span<const CrcVector> crc_known_results();

}  // namespace endatsim::master

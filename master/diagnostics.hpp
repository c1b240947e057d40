// master/diagnostics.hpp — what the subsequent electronics collect for a service engineer (spec
// appendix A3, 2.3.5.1, 3.4.2, 3.6.3, 3.6.6, 3.9.2, 3.9.6, 3.9.7, 3.9.16; the German EnDat 2.2
// brochure, both editions, "Diagnose"): the setup reads what the encoder supports and activates the valuation
// numbers (operating parameters word 3, valid after "Encoder receive reset", 3.6); the cyclic
// position reads with additional data then roll additional data 1 through the diagnosis, the
// temperatures and the additional sensors ("transmission of the diagnosis is possible in
// closed-loop operation", the same brochure), interleaved with position value 2 when the safety
// comparison needs it. A WRN bit has word 1 read.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "endatsim/protocol/indexed_table.hpp"
#include "endatsim/master/frame_result.hpp"
#include "endatsim/master/master_function.hpp"
#include "endatsim/protocol/diagnosis.hpp"
#include "endatsim/sim/parameter.hpp"
#include "endatsim/sim/time.hpp"

namespace endatsim::master {

using sim::Time;

struct DiagnosticsParams {
  bool enabled = false;
  // Operating parameters word 3 as the setup writes it (3.6.3: bits 0 .. 5 valuation numbers
  // 1 .. 6, bit 15 system-specific data), limited to what 3.9.7 word 5 says is supported
  // (the same bits).
  std::uint16_t configuration = protocol::diagnosis::kValuationNumberBits;
  bool temperatures = true;         // temperature 1 and 2 (2.3.5.1) in the rotation
  unsigned additional_sensors = 0;  // interrogations of the additional sensors per round (2.3.5.1)
  // UNCERTAIN (the German brochure, both editions: "the border areas should be suppressed in a display (definition of
  // reserve areas is necessary)"; A3: the scaling is "identical for all HEIDENHAIN encoders"
  // but not given): a valuation number below this is reported as a low function reserve.
  unsigned reserve_limit = 25;
  bool read_warnings = true;  // WRN set in additional data: read word 1 of the operating status (3.4.2)
  // ... and again this often while WRN stays set: a further warning does not change WRN (3.4.2:
  // "it is recommended to query this word at regular intervals"). 0: only when WRN appears.
  Time warnings_interval = sim::ms(100);

  // Throws std::invalid_argument naming the parameter and its limit.
  void validate() const;
};

// The scalar keys of "master.diagnostics", one row each (sim/parameter.hpp).
std::span<const sim::Parameter<DiagnosticsParams>> diagnostics_parameters();

enum class DiagnosisNoteKind : std::uint8_t {
  FunctionReserveLow,         // a valuation number below DiagnosticsParams::reserve_limit
  TemperatureAboveThreshold,  // temperature 2 above operating parameters word 6 (3.6.6)
  TemperatureAboveMaximum,    // temperature 2 above the maximum permissible encoder temperature, word 22 (3.9.16)
  Warning,                    // word 1 read after WRN, with its warnings (3.4.2)
  Setup,                      // the setup could not read or write what it needs
};
inline constexpr std::array kDiagnosisNoteKinds{DiagnosisNoteKind::FunctionReserveLow,
                                                DiagnosisNoteKind::TemperatureAboveThreshold,
                                                DiagnosisNoteKind::TemperatureAboveMaximum, DiagnosisNoteKind::Warning,
                                                DiagnosisNoteKind::Setup};
static_assert(protocol::lists_in_order(kDiagnosisNoteKinds, DiagnosisNoteKind::Setup),
              "kDiagnosisNoteKinds: every kind in the order of its value, up to the last one, Setup; a new kind goes "
              "after it, in the list and in this check");
std::string_view to_string(DiagnosisNoteKind k);  // "function_reserve_low", ...

struct DiagnosisNote {
  DiagnosisNoteKind kind = DiagnosisNoteKind::Setup;
  Time at{0};
  std::optional<std::uint64_t> frame;
  std::string message;
};

// One quantity as collected: its last value and range.
struct DiagnosisReading {
  std::uint64_t count = 0;
  unsigned last = 0, min = 0, max = 0;
  Time first_at{0}, last_at{0};
  void add(unsigned value, Time at);
};

struct DiagnosisReport {
  // What the setup read: 3.9.2 word 0, 3.9.6 word 4, 3.9.7 word 5, 3.9.16 word 22 (EnDat 2.2
  // area), 3.5 word 36 (supported warnings) and operating parameters words 3 and 6.
  std::optional<std::uint16_t> additional_data_1_support, temperature_scaling, diagnostic_status, max_temperature,
      supported_warnings, configuration, warning_threshold;
  std::optional<std::uint16_t> configuration_written;  // word 3 as the setup wrote it (then a reset)
  // `configuration` is word 3 as read, or as written once the write's echo came back.
  std::map<unsigned, DiagnosisReading> valuation_numbers;  // by A3 address
  std::optional<DiagnosisReading> temperature1, temperature2;  // 0.1 K
  std::map<unsigned, DiagnosisReading> additional_sensors;      // by address, 0.1 K
  std::uint64_t ignored_addresses = 0;  // A3: undefined and system-specific addresses
  std::optional<Time> warning_bit_at;   // WRN first seen in additional data
  std::optional<std::uint64_t> warning_bit_frame;
  std::optional<std::uint16_t> warnings;  // word 1 as last read (3.4.2)
  std::vector<DiagnosisNote> notes;
  std::size_t count(DiagnosisNoteKind k) const;
};

// What a frame was for, as far as the diagnosis cares: a cyclic read (its additional data), the
// write of operating parameters word 3 (3.6.3), or the read of word 1 after WRN (3.4.2).
enum class DiagnosisFrame : std::uint8_t { Cyclic, ConfigurationWrite, WarningsRead };

// The diagnosis as the frames bring it in: it fills the report from additional data 1 (A3
// valuation numbers, temperatures, additional sensors) and the reads of word 1, notes each
// condition once when it arises (a low function reserve, a temperature above its limit, a
// warning), and says when word 1 is due to be read. The master schedules the frames; this part
// only watches what they return.
class DiagnosisMonitor {
 public:
  explicit DiagnosisMonitor(const DiagnosticsParams& params) : params_(params) {}

  // The setup starts over: an empty report, no condition in force, WRN not seen.
  void restart();
  DiagnosisReport& report() { return report_; }
  const DiagnosisReport& report() const { return report_; }

  void on_frame(const FrameResult& f, DiagnosisFrame kind);
  // A note for `key` when `condition` arises (not again while it holds); at the frame's end, or
  // at `now` without a frame.
  void note(DiagnosisNoteKind kind, const FrameResult* f, const std::string& key, bool condition,
            const std::string& message, Time now);

  // 3.4.2: word 1 is to be read (WRN appeared, or stayed for warnings_interval).
  bool warnings_due() const { return warnings_due_; }
  void clear_warnings_due() { warnings_due_ = false; }

 private:
  void note_warning_bit(const FrameResult& f, bool warning_bit);
  void note_datum(const FrameResult& f, const AdditionalDatum& d);
  void note_temperature(const FrameResult& f, unsigned tenth_kelvin);

  const DiagnosticsParams& params_;
  DiagnosisReport report_;
  std::map<std::string, bool> conditions_;  // notes in force, by subject (noted once)
  bool warning_bit_ = false;
  bool warnings_due_ = false;
  std::optional<Time> warnings_read_at_;    // the last read of word 1 after WRN
};

// The diagnosis on top of the master's scheduler (master_function.hpp): it plans the setup a
// DiagnosisSetup operation asks for and its activation (DiagnosisActivate), and hands every frame
// to the DiagnosisMonitor.
class Diagnosis final : public MasterFunction {
 public:
  explicit Diagnosis(const DiagnosticsParams& params) : params_(params), monitor_(params) {}

  const DiagnosisReport& report() const { return monitor_.report(); }

  Planned plan(const FunctionContext& ctx, Sequence& plan) override;
  void on_frame(FrameResult& f, const FunctionContext& ctx) override;
  std::optional<StatusRead> status_read_due() const override;
  void status_read_planned() override { monitor_.clear_warnings_due(); }

 private:
  void plan_setup(Sequence& plan);
  void plan_activation(const FunctionContext& ctx, Sequence& plan);

  const DiagnosticsParams& params_;
  DiagnosisMonitor monitor_;
};

}  // namespace endatsim::master

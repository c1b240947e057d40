// The diagnosis the master collects (diagnostics.hpp): its setup and activation, and what the
// frames bring in.
#include "endatsim/master/diagnostics.hpp"

#include <algorithm>
#include <stdexcept>

#include "endatsim/master/parameter_book.hpp"
#include "endatsim/protocol/diagnosis.hpp"
#include "endatsim/protocol/parameters.hpp"
#include "endatsim/sim/text.hpp"

namespace endatsim::master {
namespace {

using MC = protocol::ModeCommand;
using I = protocol::Information;
using P = Operation::Purpose;
using K = DiagnosisNoteKind;
namespace dg = protocol::diagnosis;

std::string hex(std::uint16_t v) { return sim::hex_h(v, 4); }

namespace word = protocol::word;
// Words the setup reads from the EnDat 2.2 area (3.9.2, 3.9.6, 3.9.7, 3.9.16) ...
constexpr unsigned kAdditionalData1Support = word::kAdditionalData1Support, kTemperatureScaling = word::kTemperatureScaling,
                   kDiagnosticStatus = word::kDiagnosticStatus, kMaxTemperature = word::kMaxEncoderTemperature;
// ... and with 2.1 frames: word 36 (supported warnings) and 37 (command set) in A5, operating
// parameters words 3 and 6 (3.6.3, 3.6.6).
constexpr std::uint8_t kSupportedWarnings = word::manufacturer_address(word::kSupportedWarnings),
                       kCommandSet = word::manufacturer_address(word::kCommandSet),
                       kConfiguration = word::kDiagnosticsConfiguration, kWarningThreshold = word::kTemperatureWarningThreshold;

}  // namespace

std::string_view to_string(DiagnosisNoteKind k) {
  switch (k) {
    case K::FunctionReserveLow: return "function_reserve_low";
    case K::TemperatureAboveThreshold: return "temperature_above_threshold";
    case K::TemperatureAboveMaximum: return "temperature_above_maximum";
    case K::Warning: return "warning";
    case K::Setup: return "setup";
  }
  return "?";
}

void DiagnosticsParams::validate() const {
  const auto allowed = static_cast<std::uint16_t>(dg::kValuationNumberBits | dg::kSystemSpecificDataBit);
  if ((configuration & ~allowed) != 0)
    throw std::invalid_argument("master diagnostics configuration may set only bits 0 .. 5 (valuation numbers) and 15 "
                                "(system-specific data) of operating parameters word 3 (3.6.3), got " + hex(configuration));
  if (auto why = sim::first_out_of_range(diagnostics_parameters(), *this, "master diagnostics"))
    throw std::invalid_argument(*why);
}

void DiagnosisReading::add(unsigned value, Time at) {
  if (count == 0) {
    min = max = value;
    first_at = at;
  }
  min = std::min(min, value);
  max = std::max(max, value);
  last = value;
  last_at = at;
  ++count;
}

std::size_t DiagnosisReport::count(DiagnosisNoteKind k) const {
  return static_cast<std::size_t>(std::count_if(notes.begin(), notes.end(), [k](const DiagnosisNote& n) { return n.kind == k; }));
}

// ---- parameters read ------------------------------------------------------------------------

// ---- the setup ----------------------------------------------------------------------------------

// The German brochure (older edition), "Aktivieren der Diagnose": read what the encoder supports (3.9.2, 3.9.7) and how it
// scales temperatures (3.9.6, 3.9.16; word 36 for the warnings), and the operating parameters
// in force (3.6.3, 3.6.6); DiagnosisActivate then writes word 3 if needed.
void Diagnosis::plan_setup(Sequence& plan) {
  plan.frame(MC::SelectionOfMemoryArea, mrs_of(protocol::MemoryArea::Manufacturer3));
  plan.frame(MC::EncoderSendParameters, kSupportedWarnings);
  plan.frame(MC::EncoderSendParameters, kCommandSet);
  plan.frame(MC::SelectionOfMemoryArea, mrs_of(protocol::MemoryArea::OperatingParameters));
  plan.frame(MC::EncoderSendParameters, kConfiguration);
  plan.frame(MC::EncoderSendParameters, kWarningThreshold);
  plan.add(Operation::Kind::ReadEndat22Area).endat22_words =
      std::uint64_t{1} << kAdditionalData1Support | std::uint64_t{1} << kTemperatureScaling |
      std::uint64_t{1} << kDiagnosticStatus | std::uint64_t{1} << kMaxTemperature;
  plan.add(Operation::Kind::DiagnosisActivate);
  monitor_.restart();
}

// 3.6: "changes to the values do not become valid until the mode command 'Encoder receive
// reset' is transmitted"; the reset also ends the selection of additional data (2.7).
void Diagnosis::plan_activation(const FunctionContext& ctx, Sequence& plan) {
  DiagnosisReport& r = monitor_.report();
  const auto parameter = [&ctx](std::uint8_t mrs, std::uint8_t address) { return ctx.book.parameter(mrs, address); };
  const std::uint8_t a5 = mrs_of(protocol::MemoryArea::Manufacturer3), a7 = mrs_of(protocol::MemoryArea::OperatingParameters);
  r.supported_warnings = parameter(a5, kSupportedWarnings);
  r.configuration = parameter(a7, kConfiguration);
  r.warning_threshold = parameter(a7, kWarningThreshold);
  r.additional_data_1_support = ctx.book.endat22_word(kAdditionalData1Support);
  r.temperature_scaling = ctx.book.endat22_word(kTemperatureScaling);
  r.diagnostic_status = ctx.book.endat22_word(kDiagnosticStatus);
  r.max_temperature = ctx.book.endat22_word(kMaxTemperature);
  const auto word37 = parameter(a5, kCommandSet);
  if (!word37 || !protocol::parameters::decode_command_set(*word37).endat22) {
    monitor_.note(K::Setup, nullptr, "setup", true,
                    "the encoder has no EnDat 2.2 command set (word 37): no diagnosis through additional data", ctx.now);
    return;
  }
  if (!r.configuration || !r.diagnostic_status || !r.additional_data_1_support) {
    monitor_.note(K::Setup, nullptr, "setup", true,
                    "the diagnostic status (3.9.7) or the configuration (3.6.3) could not be read", ctx.now);
  } else {
    if (r.temperature_scaling && !dg::temperature_scaling(*r.temperature_scaling))
      monitor_.note(K::Setup, nullptr, "scaling", true,
                      "temperature scaling word 4 = " + hex(*r.temperature_scaling) +
                          " is not the 0.1 K the spec defines (3.9.6); temperatures shown as 0.1 K",
                      ctx.now);
    // 3.9.7: word 5 has the bits of word 3 for what is supported.
    const auto wanted = static_cast<std::uint16_t>(params_.configuration & *r.diagnostic_status);
    if (wanted != *r.configuration) {
      r.configuration_written = wanted;
      plan.frame(MC::SelectionOfMemoryArea, a7);
      plan.frame(MC::EncoderReceiveParameters, kConfiguration, wanted, P::DiagnosisConfiguration);
      plan.frame(MC::EncoderReceiveReset);
    }
  }
  // Its flow chart: then "Encoder send position values with additional data" with the
  // diagnosis selected (the reads of the 2.2 area left memory parameters selected).
  plan.frame(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, protocol::selection_mrs(I::Diagnosis));
}

Planned Diagnosis::plan(const FunctionContext& ctx, Sequence& plan) {
  switch (ctx.operation.kind) {
    case Operation::Kind::DiagnosisSetup:
      plan_setup(plan);
      return {Planned::What::Expanded};
    case Operation::Kind::DiagnosisActivate:
      plan_activation(ctx, plan);
      return {Planned::What::Expanded};
    default: return {};
  }
}

void Diagnosis::on_frame(FrameResult& f, const FunctionContext& ctx) {
  const P p = ctx.operation.purpose;
  monitor_.on_frame(f, p == P::DiagnosisConfiguration ? DiagnosisFrame::ConfigurationWrite
                       : p == P::DiagnosisWarnings    ? DiagnosisFrame::WarningsRead
                                                      : DiagnosisFrame::Cyclic);
}

// 3.4.2: word 1 says which warning it was.
std::optional<StatusRead> Diagnosis::status_read_due() const {
  if (!monitor_.warnings_due()) return std::nullopt;
  return StatusRead{protocol::word::kWarnings, P::DiagnosisWarnings};
}

// ---- what the frames carry ----------------------------------------------------------------------

void DiagnosisMonitor::restart() {
  report_ = DiagnosisReport{};
  conditions_.clear();
  warning_bit_ = false;
  warnings_read_at_.reset();
}

void DiagnosisMonitor::note(DiagnosisNoteKind kind, const FrameResult* f, const std::string& key, bool condition,
                            const std::string& message, Time now) {
  bool& in_force = conditions_[key];
  const bool new_condition = condition && !in_force;
  in_force = condition;
  if (!new_condition) return;
  DiagnosisNote n;
  n.kind = kind;
  n.at = f != nullptr ? f->end : now;
  if (f != nullptr) n.frame = f->index;
  n.message = message;
  report_.notes.push_back(std::move(n));
}

void DiagnosisMonitor::on_frame(const FrameResult& f, DiagnosisFrame kind) {
  if (!params_.enabled) return;
  if (kind == DiagnosisFrame::ConfigurationWrite) {
    if (f.outcome == FrameOutcome::Ok) report_.configuration = protocol::payload_parameter(*f.payload);
    else
      note(K::Setup, &f, "configuration", true,
           "operating parameters word 3 could not be written (" + std::string(to_string(f.outcome)) + "); " +
               hex(report_.configuration.value_or(0)) + " stays in force",
           f.end);
    return;
  }
  if (f.outcome != FrameOutcome::Ok) return;
  if (kind == DiagnosisFrame::WarningsRead) {
    warnings_read_at_ = f.end;
    report_.warnings = f.echo_parameter;
    const bool any = f.echo_parameter != 0;
    note(K::Warning, &f, "word 1 " + hex(f.echo_parameter), any,
         "word 1 = " + hex(f.echo_parameter) + ": " +
             protocol::parameters::bits_string(f.echo_parameter, protocol::parameters::warning_bit_names()),
         f.end);
    return;
  }
  bool warning_bit = false;
  bool seen = false;
  for (const auto& d : f.additional_data) {
    if (!d.crc_ok) continue;
    seen = true;
    warning_bit = warning_bit || (d.status & protocol::AdditionalDataStatus::kWarning) != 0;
    note_datum(f, d);
  }
  if (seen) note_warning_bit(f, warning_bit);
}

// 3.4.2: "query the group bit for warnings (WRN)"; word 1 says which, when WRN appears and at
// regular intervals while it stays (a further warning leaves WRN as it is).
void DiagnosisMonitor::note_warning_bit(const FrameResult& f, bool warning_bit) {
  if (warning_bit && !report_.warning_bit_at) {
    report_.warning_bit_at = f.end;
    report_.warning_bit_frame = f.index;
  }
  const bool again = warnings_read_at_ && params_.warnings_interval > Time::zero() &&
                     f.end - *warnings_read_at_ >= params_.warnings_interval;
  if (warning_bit && (!warning_bit_ || again)) warnings_due_ = params_.read_warnings;
  warning_bit_ = warning_bit;
}

void DiagnosisMonitor::note_datum(const FrameResult& f, const AdditionalDatum& d) {
  DiagnosisReport& r = report_;
  switch (d.information()) {
    case I::Diagnosis: {
      const unsigned address = protocol::datum_address(d.data), value = protocol::datum_byte(d.data);
      const auto a = dg::decode_diagnosis_address(address);
      const std::uint16_t active = r.configuration.value_or(params_.configuration);
      if (!a || a->bit >= dg::kValuationNumbers || ((active >> a->bit) & 1U) == 0) {
        ++r.ignored_addresses;  // A3: "the subsequent electronics must ignore undefined addresses"
        return;
      }
      r.valuation_numbers[address].add(value, f.end);
      note(K::FunctionReserveLow, &f, "valuation number at " + std::to_string(address), value < params_.reserve_limit,
           "valuation number " + std::to_string(a->bit + 1) + " (address " + std::to_string(address) + ") = " +
               std::to_string(value) + ", below the reserve limit " + std::to_string(params_.reserve_limit),
           f.end);
      return;
    }
    case I::Temperature1:
      (r.temperature1 ? *r.temperature1 : r.temperature1.emplace()).add(d.data, f.end);
      return;
    case I::Temperature2:
      (r.temperature2 ? *r.temperature2 : r.temperature2.emplace()).add(d.data, f.end);
      note_temperature(f, d.data);
      return;
    case I::AdditionalSensors: {
      const auto v = dg::decode_additional_sensor(d.data);
      r.additional_sensors[v.address].add(v.tenth_kelvin, f.end);
      return;
    }
    default: return;
  }
}

// 3.6.6: only the internal sensor (temperature 2) triggers the warning at word 6; it is also held
// against the maximum permissible encoder temperature (3.9.16, 0: none). Temperature 1 and the
// additional sensors measure the motor (2.3.5.1): no encoder limit applies to them.
void DiagnosisMonitor::note_temperature(const FrameResult& f, unsigned tenth_kelvin) {
  const DiagnosisReport& r = report_;
  const std::string what = "temperature 2 " + dg::temperature_string(tenth_kelvin);
  if (r.warning_threshold && *r.warning_threshold != 0) {
    const auto exceeded = protocol::parameters::kWarningTemperatureExceeded;
    const bool supported = (r.supported_warnings.value_or(exceeded) & exceeded) != 0;
    note(K::TemperatureAboveThreshold, &f, "threshold", tenth_kelvin > *r.warning_threshold,
         what + " above the warning threshold " + dg::temperature_string(*r.warning_threshold) +
             " (operating parameters word 6)" + (supported ? "" : "; word 36 says the encoder has no such warning"),
         f.end);
  }
  if (r.max_temperature && *r.max_temperature != 0)
    note(K::TemperatureAboveMaximum, &f, "maximum", tenth_kelvin > *r.max_temperature,
         what + " above the maximum permissible encoder temperature " + dg::temperature_string(*r.max_temperature) +
             " (word 22)",
         f.end);
}

}  // namespace endatsim::master

#include "endatsim/scenarios/decoder_tables.hpp"

#include <cctype>
#include <stdexcept>

#include "endatsim/checker/clock_fit.hpp"
#include "endatsim/checker/frame_decoder.hpp"
#include "endatsim/checker/timing_checker.hpp"
#include "endatsim/protocol/additional_data.hpp"
#include "endatsim/protocol/crc.hpp"
#include "endatsim/protocol/error_handling.hpp"
#include "endatsim/protocol/frame.hpp"
#include "endatsim/protocol/memory_area.hpp"
#include "endatsim/protocol/mode_command.hpp"
#include "endatsim/protocol/parameters.hpp"
#include "endatsim/protocol/timing.hpp"

namespace endatsim::scenarios {
namespace {

using nlohmann::ordered_json;
namespace limit = protocol::limit;
namespace position = protocol::frame_position;

std::string version_text(protocol::EndatVersion v) { return v == protocol::EndatVersion::V2_1 ? "2.1" : "2.2"; }

std::string answer_text(protocol::AnswerFormat a) {
  switch (a) {
    case protocol::AnswerFormat::Position: return "position";
    case protocol::AnswerFormat::TestValues: return "test_values";
    case protocol::AnswerFormat::Parameter: return "parameter";
  }
  throw std::logic_error("answer format");
}

// "start bit" -> "start_bit", "F1" -> "f1": a name a program can use as a key.
std::string key_of(std::string_view name) {
  std::string key;
  for (const char c : name) key += c == ' ' ? '_' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return key;
}

// A layout's fields in wire order; `variable` is the field whose width the decoder sets (the
// position, from its option or word 13), exported with width null.
ordered_json layout_json(const protocol::Layout& layout, std::optional<protocol::Field> variable = std::nullopt) {
  ordered_json fields = ordered_json::array();
  for (const auto& f : layout.fields()) {
    ordered_json j;
    j["field"] = key_of(protocol::field_name(f.field));
    j["name"] = protocol::field_name(f.field);
    if (variable == f.field) j["width"] = nullptr;
    else j["width"] = f.width;
    j["order"] = f.order == protocol::BitOrder::LsbFirst ? "lsb_first" : "msb_first";
    fields.push_back(j);
  }
  return fields;
}

ordered_json limits_json() {
  ordered_json l;
  const auto time = [&](const char* name, sim::Time t) { l[std::string(name) + "_ps"] = t.count(); };
  const auto hertz = [&](const char* name, sim::Hertz f) { l[std::string(name) + "_hz"] = f; };
  hertz("fc_min", limit::kFcMin);
  hertz("fc_max_without_compensation", limit::kFcMaxWithoutCompensation);
  hertz("fc_max_with_compensation", limit::kFcMaxWithCompensation);
  hertz("fc_max_special", limit::kFcMaxSpecial);
  l["compensated_cable_max_m"] = limit::kCompensatedCableMaxMetres;
  hertz("measurement_fc_min", limit::kMeasurementFcMin);
  hertz("measurement_fc_max", limit::kMeasurementFcMax);
  l["measurement_counter_factor"] = limit::kMeasurementCounterFactor;
  l["measurement_counter_tolerance_percent"] = limit::kMeasurementCounterTolerancePercent;
  l["measurements_min"] = limit::kMeasurementsMin;
  time("calculation_time_max", limit::kCalculationTimeMax);
  l["continuous_clock_max_low_bits"] = limit::kContinuousClockMaxLowBits;
  time("memory_access_max", limit::kMemoryAccessMax);
  time("recovery_time_min", limit::kRecoveryTimeMin);
  time("recovery_time_max", limit::kRecoveryTimeMax);
  time("short_recovery_time_min", limit::kShortRecoveryTimeMin);
  time("short_recovery_time_max", limit::kShortRecoveryTimeMax);
  hertz("short_recovery_time_fc_min", limit::kShortRecoveryTimeFcMin);
  time("recovery_time_2_min", limit::kRecoveryTime2Min);
  time("start_delay", limit::kStartDelay);
  time("start_delay_at_16mhz", limit::kStartDelayAt16MHz);
  time("data_delay_base", limit::kDataDelayBase);
  time("data_delay_per_metre", limit::kDataDelayPerMetre);
  l["data_delay_tolerance_percent"] = limit::kDataDelayTolerancePercent;
  time("pulse_width_min", limit::kPulseWidthMin);
  time("pulse_high_max", limit::kPulseHighMax);
  l["on_off_ratio_error_percent"] = limit::kOnOffRatioErrorPercent;
  time("period_at_fc_min", limit::kPeriodAtFcMin);
  time("time_between_cycles_min", limit::kTimeBetweenCyclesMin);
  time("error_recovery_wait", limit::kErrorRecoveryWait);
  time("power_on_t1_min", limit::kPowerOnT1Min);
  time("power_on_t2_min", limit::kPowerOnT2Min);
  time("power_on_t2_max", limit::kPowerOnT2Max);
  time("power_on_pulse_min", limit::kPowerOnPulseMin);
  time("power_on_t3_min", limit::kPowerOnT3Min);
  time("power_on_t3_max", limit::kPowerOnT3Max);
  return l;
}

ordered_json mode_commands_json() {
  ordered_json commands = ordered_json::array();
  for (const auto& m : protocol::mode_commands()) {
    ordered_json j;
    j["key"] = m.key;
    j["name"] = m.name;
    j["bits"] = m.bits;
    j["version"] = version_text(m.version);
    j["payload_bits"] = m.payload_bits;
    j["answer"] = answer_text(m.answer);
    j["supplement"] = m.supplement;
    commands.push_back(j);
  }
  return commands;
}

ordered_json additional_data_json() {
  using S = protocol::AdditionalDataStatus;
  ordered_json a;
  a["datum_bits"] = protocol::kAdditionalDatumBits;
  a["status"] = {{"warning", S::kWarning}, {"reference_mark", S::kReferenceMark}, {"busy", S::kBusy},
                 {"information", S::kInformation}};
  ordered_json codes = ordered_json::array();
  for (const auto& c : protocol::information_codes()) {
    ordered_json j;
    j["code"] = static_cast<unsigned>(c.code);
    j["key"] = c.key;
    j["name"] = c.name;
    j["additional_data"] = protocol::is_additional_data_2(c.code) ? 2 : 1;
    codes.push_back(j);
  }
  a["information"] = codes;
  // 2.4.2.2: the MRS codes that select (or stop) additional data, and the two that stop it.
  ordered_json selecting = ordered_json::array();
  for (unsigned mrs = 0; mrs <= 0xFF; ++mrs)
    if (protocol::selects_additional_data(static_cast<std::uint8_t>(mrs))) selecting.push_back(mrs);
  a["selecting_mrs"] = selecting;
  a["stop_mrs"] = {{"1", protocol::kStopAdditionalData1}, {"2", protocol::kStopAdditionalData2}};
  return a;
}

ordered_json memory_areas_json() {
  ordered_json areas = ordered_json::array();
  for (const auto& m : protocol::memory_areas())
    areas.push_back({{"mrs", m.mrs}, {"key", m.key}, {"name", m.name}, {"endat22_only", m.endat22_only}});
  return areas;
}

ordered_json error_handling_json() {
  ordered_json causes = ordered_json::array();
  for (const auto& c : protocol::kErrorCauses)
    causes.push_back({{"cause", static_cast<unsigned>(c.cause)}, {"type", static_cast<unsigned>(c.type)}, {"text", c.text}});
  return causes;
}

ordered_json checks_json() {
  ordered_json rows = ordered_json::array();
  for (const auto& r : protocol::timing_rows()) {
    ordered_json j;
    j["check"] = r.check;
    j["symbol"] = r.symbol;
    j["designation"] = r.designation;
    j["section"] = r.section;
    j["min"] = r.min;
    j["max"] = r.max;
    j["condition"] = r.condition;
    j["observed"] = r.observed;
    j["evidence"] = r.evidence == protocol::Evidence::Wires ? "wires" : "master_declaration";
    rows.push_back(j);
  }
  return rows;
}

}  // namespace

ordered_json decoder_tables() {
  ordered_json t;
  t["format"] = 1;
  t["frame_position"] = {{"frame_start", position::kFrameStart},       {"master_drives", position::kMasterDrives},
                         {"first_mode_bit", position::kFirstModeBit},  {"last_mode_bit", position::kLastModeBit},
                         {"mode_bits", position::kModeBits},           {"turnaround", position::kTurnaround},
                         {"earliest_start_bit", position::kEarliestStartBit}};
  t["limits"] = limits_json();
  const protocol::CrcConfig spec_crc{};
  t["crc"] = {{"bits", protocol::kCrcBits},
              {"polynomial", protocol::kCrcPolynomial},
              {"preset", spec_crc.preset},
              {"final_inversion", spec_crc.final_inversion}};
  t["mode_commands"] = mode_commands_json();
  t["payload_bits"] = protocol::kPayloadBits;
  using protocol::EndatVersion;
  using protocol::Field;
  t["layouts"] = {{"position_2_1", layout_json(protocol::position_frame_layout(EndatVersion::V2_1, 1), Field::Position)},
                  {"position_2_2", layout_json(protocol::position_frame_layout(EndatVersion::V2_2, 1), Field::Position)},
                  {"test_values", layout_json(protocol::test_values_layout())},
                  {"parameter", layout_json(protocol::parameter_frame_layout())},
                  {"payload", layout_json(protocol::payload_layout())},
                  {"additional_datum", layout_json(protocol::additional_datum_layout())},
                  {"supplement", layout_json(protocol::supplement_layout())}};
  t["additional_data"] = additional_data_json();
  t["memory_areas"] = memory_areas_json();
  t["error_handling"] = error_handling_json();  // appendix A2
  t["position_format"] = {{"area_mrs", protocol::info(protocol::MemoryArea::Manufacturer1).mrs},
                          {"word", protocol::word::kPositionFormat},
                          {"bits_mask", protocol::parameters::decode_position_bits(0xFFFF)}};
  // 3.4.4: word 3 of the operating status selects the short recovery time I; a reset activates it.
  const auto& short_tm = protocol::parameters::function_initialization_bits()[static_cast<std::size_t>(
      protocol::parameters::EncoderFunction::ShortRecoveryTime)];
  t["function_initialization"] = {{"area_mrs", protocol::info(protocol::MemoryArea::OperatingStatus).mrs},
                                  {"word", protocol::word::kFunctionInitialization},
                                  {"short_recovery_time_mask", short_tm.mask},
                                  {"short_recovery_time_activated", short_tm.activated}};
  const checker::DecoderParams d{};
  t["decoder"] = {{"position_bits", d.position_bits},
                  {"clock_to_data_ps", d.clock_to_data.count()},
                  {"t_m_ps", d.t_m.count()},
                  {"supplement_ignore_clocks", d.supplement_ignore_clocks},
                  {"fit_max_edges", checker::kMaxFitEdges},
                  {"f_c_tolerance_ppm", checker::CheckerParams{}.f_c_tolerance_ppm}};
  t["checks"] = checks_json();
  return t;
}

std::string decoder_tables_json() { return decoder_tables().dump(2) + "\n"; }

std::string decoder_tables_python() {
  return "# The EnDat tables of endatsim (protocol/, and the defaults of checker/frame_decoder.hpp), as\n"
         "# `endatsim checks --python` writes them. Do not edit: tests/timing_table_test.cpp fails when this\n"
         "# file differs from what the tables generate. Regenerate with\n"
         "#   build/tools/endatsim checks --python > tools/sigrok/endat/tables.py\n"
         "import json\n"
         "\n"
         "TABLES = json.loads(r'''\n" +
         decoder_tables_json() + "''')\n";
}

}  // namespace endatsim::scenarios

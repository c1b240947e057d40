#include "endatsim/scenarios/parameter_docs.hpp"

#include <span>
#include <string_view>

#include "endatsim/checker/timing_checker.hpp"
#include "endatsim/input/json_input.hpp"
#include "endatsim/line/line.hpp"
#include "endatsim/master/master.hpp"
#include "endatsim/protocol/additional_data.hpp"
#include "endatsim/protocol/crc_parameters.hpp"
#include "endatsim/protocol/diagnosis.hpp"
#include "endatsim/protocol/frame.hpp"
#include "endatsim/protocol/memory_area.hpp"
#include "endatsim/protocol/timing.hpp"
#include "endatsim/scenarios/event_kinds.hpp"
#include "endatsim/scenarios/list_keys.hpp"
#include "endatsim/scenarios/operation_kinds.hpp"
#include "endatsim/sim/parameter.hpp"
#include "endatsim/slave/encoder_params.hpp"

namespace endatsim::scenarios {
namespace {

using nlohmann::json;
using sim::ParameterType;

std::string_view type_name(ParameterType t) {
  switch (t) {
    case ParameterType::Duration: return "duration";
    case ParameterType::Frequency: return "frequency";
    case ParameterType::Number: return "number";
    case ParameterType::Count: return "integer";
    case ParameterType::Flag: return "boolean";
    case ParameterType::Word: return "word";
    case ParameterType::Choice: return "choice";
  }
  return "";
}

template <class Params>
std::string default_text(const sim::Parameter<Params>& row, const Params& defaults) {
  return row.default_text.empty() ? sim::value_text(row, defaults) : std::string(row.default_text);
}

template <class Params>
std::string description(const sim::Parameter<Params>& row, const Params& defaults) {
  std::string d(row.help);
  if (!row.section.empty()) d += " D297403 " + std::string(row.section) + ".";
  const auto type = sim::type_of(row);
  const bool narrow_word = type == ParameterType::Word && row.max != 0xFF && row.max != 0xFFFF;
  if (type == ParameterType::Duration || type == ParameterType::Frequency || narrow_word)
    d += " Range: " + sim::range_text(row) + ".";
  if (row.required) return d + " Required.";
  return d + " Default: " + default_text(row, defaults) + ".";
}

template <class Params>
json property(const sim::Parameter<Params>& row, const Params& defaults) {
  json p = {{"description", description(row, defaults)}};
  switch (sim::type_of(row)) {
    case ParameterType::Duration: p["$ref"] = "#/$defs/duration"; break;
    case ParameterType::Frequency: p["$ref"] = "#/$defs/frequency"; break;
    case ParameterType::Number:
      p["type"] = "number";
      p["minimum"] = row.min;
      p["maximum"] = row.max;
      break;
    case ParameterType::Count:
      p["type"] = "integer";
      p["minimum"] = row.min;
      p["maximum"] = row.max;
      break;
    case ParameterType::Flag: p["type"] = "boolean"; break;
    case ParameterType::Word:
      if (row.max == 0xFF || row.max == 0xFFFF) {
        p["$ref"] = row.max == 0xFF ? "#/$defs/byte" : "#/$defs/word";
      } else {  // fewer bits: the integer's range is checked here, a hex string's by the loader
        p["oneOf"] = json::array({json{{"type", "integer"}, {"minimum", 0}, {"maximum", row.max}},
                                  json{{"type", "string"}, {"pattern", "^(0[xX][0-9a-fA-F]{1,4}|[0-9]{1,5})$"}}});
      }
      break;
    case ParameterType::Choice: {
      json names = json::array();
      for (const auto name : std::get<sim::ChoiceField<Params>>(row.field).names) names.push_back(std::string(name));
      p["enum"] = names;
      break;
    }
  }
  return p;
}

std::string cell(std::string_view text) {  // a Markdown table cell: pipes escaped
  std::string out;
  for (const char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

template <class Params>
std::string table(std::span<const sim::Parameter<Params>> rows, const Params& defaults) {
  std::string t = "| key | type | range | default | D297403 | meaning |\n|---|---|---|---|---|---|\n";
  for (const auto& row : rows)
    t += "| `" + std::string(row.key) + "` | " + std::string(type_name(sim::type_of(row))) + " | " +
         cell(sim::range_text(row)) + " | " + (row.required ? "required" : cell(default_text(row, defaults))) + " | " +
         (row.section.empty() ? "model" : std::string(row.section)) + " | " + cell(row.help) + " |\n";
  return t;
}

}  // namespace

namespace {

// Where each object's rows go: its title in docs/parameters.md and its properties in the schema.
template <class Params>
struct Section {
  std::string_view title;    // the scenario's JSON path of the object
  std::string_view pointer;  // the schema's JSON pointer of its "properties"
  std::span<const sim::Parameter<Params>> rows;
  std::string_view also_pointer = {};  // a second object with the same rows
};

template <class F>
void for_each_section(F&& f) {
  f(Section<line::LineParams>{"line", "/$defs/line/properties", line::line_parameters()}, line::LineParams{});
  f(Section<line::TransceiverParams>{"line.master_transceiver, line.encoder_transceiver", "/$defs/transceiver/properties",
                                     line::transceiver_parameters()},
    line::LineParams{}.master);
  f(Section<slave::EncoderParams>{"encoder", "/$defs/encoder/properties", slave::encoder_parameters()}, slave::EncoderParams{});
  f(Section<slave::Sensors>{"encoder.sensors", "/$defs/encoder/properties/sensors/properties", slave::sensor_parameters()},
    slave::Sensors{});
  f(Section<slave::MotionProfile>{"encoder.motion", "/$defs/encoder/properties/motion/properties",
                                  slave::motion_parameters()},
    slave::MotionProfile{});
  f(Section<protocol::CrcConfig>{"encoder.crc, master.crc", "/$defs/encoder/properties/crc/properties",
                                 protocol::crc_generator_parameters(), "/$defs/master/properties/crc/properties"},
    protocol::CrcConfig{});
  f(Section<master::MasterParams>{"master", "/$defs/master/properties", master::master_parameters()}, master::MasterParams{});
  f(Section<master::CrcCheck>{"master.crc", "/$defs/master/properties/crc/properties", master::crc_check_parameters()},
    master::CrcCheck{});
  f(Section<master::MasterParams::PowerOnSequence>{"master.power_on", "/$defs/master/properties/power_on/properties",
                                                   master::power_on_parameters()},
    master::MasterParams{}.power_on);
  f(Section<master::DelayMeasurementParams>{"master.delay_measurement",
                                            "/$defs/master/properties/delay_measurement/properties",
                                            master::delay_measurement_parameters()},
    master::DelayMeasurementParams{});
  f(Section<master::CarefulMaster>{"master.careful", "/$defs/master/properties/careful/properties",
                                   master::careful_parameters()},
    master::CarefulMaster{});
  f(Section<master::SafetyParams>{"master.safety", "/$defs/master/properties/safety/properties",
                                  master::safety_parameters()},
    master::SafetyParams{});
  f(Section<master::MotionSetpoint>{"master.safety.setpoint", "/$defs/master/properties/safety/properties/setpoint/properties",
                                    master::setpoint_parameters()},
    master::MotionSetpoint{});
  f(Section<master::DiagnosticsParams>{"master.diagnostics", "/$defs/master/properties/diagnostics/properties",
                                       master::diagnostics_parameters()},
    master::DiagnosticsParams{});
  f(Section<checker::CheckerParams>{"checker", "/$defs/checker/properties", checker::checker_parameters()},
    checker::CheckerParams{});
}

}  // namespace

namespace {

std::string kind_description(const EventKindRow& k) {
  return std::string(k.help) + (k.section.empty() ? "" : " D297403 " + std::string(k.section) + ".");
}

// The schema of an event kind's value; none for the kinds whose schema is written by hand.
std::optional<json> event_kind_schema(const EventKindRow& k) {
  using Body = EventKindRow::Body;
  const Event defaults;
  if (k.body == Body::Custom) return std::nullopt;
  if (k.body == Body::Value) {
    json p = property(k.fields.front(), defaults);
    p["description"] = kind_description(k);
    return p;
  }
  json properties = json::object(), required = json::array();
  for (const auto& row : k.fields) {
    properties[std::string(row.key)] = property(row, defaults);
    if (row.required) required.push_back(std::string(row.key));
  }
  json p = {{"description", kind_description(k)}, {"type", "object"}, {"additionalProperties", false},
            {"properties", properties}};
  if (!required.empty()) p["required"] = required;
  return p;
}

// The events' tables: the trigger keys, then each kind with what it does and its keys.
std::string event_tables_markdown() {
  using Body = EventKindRow::Body;
  std::string md = "\n## events\n\nEvery event has a trigger and exactly one kind key.\n\n" +
                   table(event_trigger_parameters(), Event{});
  for (const auto& k : event_kinds()) {
    md += "\n### events: " + std::string(k.key) + "\n\n" + kind_description(k) + "\n\n";
    if (k.body == Body::Object) md += table(k.fields, Event{});
    else if (k.body == Body::Value) md += "The value is a duration, " + sim::range_text(k.fields.front()) + ".\n";
    else md += "Keys: " + std::string(k.fields_text) + ".\n";
  }
  return md;
}

std::string operation_description(const OperationKindRow& k) {
  return std::string(k.help) + (k.section.empty() ? "" : " D297403 " + std::string(k.section) + ".");
}

// An operation's "mode_bits": the six bits of a disturbed mode command (2.3: RE3 .. RE8).
json mode_bits_property() {
  return {{"description", "Six other bits to send (a disturbed mode command)."},
          {"type", "string"},
          {"pattern", "^[01]{" + std::to_string(protocol::frame_position::kModeBits) + "}$"}};
}

// The schema of the script's operations: "op" and "at" for all, and for each operation (the
// operation's block in "allOf", in the rows' order) the properties its rows generate and the keys
// it requires.
void add_operation_schema(json& out) {
  json names = json::array();
  for (const auto& k : operation_kinds()) names.push_back(std::string(k.key));
  json common = {{"op", {{"description", "What the operation does (docs/parameters.md, \"script\")."}, {"enum", names}}}};
  for (const auto& row : operation_common_parameters()) common[std::string(row.key)] = property(row, master::Operation{});
  out["/$defs/operation/properties"] = {{"properties", common}, {"required", json::array({"op"})}};
  for (std::size_t i = 0; i < operation_kinds().size(); ++i) {
    const auto& k = operation_kinds()[i];
    json properties = json::object(), required = json::array();
    for (const auto& row : k.fields) {
      properties[std::string(row.key)] = property(row, k.defaults);
      if (row.required) required.push_back(std::string(row.key));
    }
    for (const auto& other : k.other_keys) {
      if (other.required) required.push_back(std::string(other.key));
      if (other.key == "mode_bits") properties["mode_bits"] = mode_bits_property();
    }
    out["/$defs/operation/allOf/" + std::to_string(i) + "/then/properties"] = {{"properties", properties},
                                                                               {"required", required}};
  }
}

std::string mode_bits_text(protocol::ModeCommand c) {
  return protocol::mode_bits_string(protocol::info(c).bits) + " (" + std::string(protocol::info(c).key) + ")";
}

// The script's tables: "at", then each operation with what it does, its mode commands and keys.
std::string operation_tables_markdown() {
  std::string md = "\n## script\n\nEvery operation has an `op` and may have:\n\n" +
                   table(operation_common_parameters(), master::Operation{});
  for (const auto& k : operation_kinds()) {
    md += "\n### script: " + std::string(k.key) + "\n\n" + operation_description(k) + "\n";
    if (k.command && k.command_22)
      md += "\nMode command: " + mode_bits_text(*k.command) + ", with `command_type` `\"2.2\"` " +
            mode_bits_text(*k.command_22) + ".\n";
    else if (k.command || k.command_22)
      md += "\nMode command: " + mode_bits_text(k.command ? *k.command : *k.command_22) + ".\n";
    if (k.sends_frames) md += "\nIt may carry `expect`, judged on its last frame.\n";
    if (!k.fields.empty()) md += "\n" + table(k.fields, k.defaults);
    if (!k.other_keys.empty()) md += "\n";
    for (const auto& other : k.other_keys)
      md += "- `" + std::string(other.key) + "`" + (other.required ? " (required)" : "") + ": " +
            std::string(other.text) + "\n";
  }
  return md;
}

}  // namespace

namespace {

// The properties of the keys that hold lists, maps or values in a form of their own, where a bound
// of theirs is checked by the loader: generated from the constants the loader uses
// (scenarios/list_keys.hpp, protocol/), so that the schema cannot drift from it. They carry no
// "required": their objects' required keys are the rows' or written by hand.
void add_list_key_schema(json& out) {
  namespace dg = protocol::diagnosis;
  const auto add = [&out](const std::string& pointer, const std::string& key, json property) {
    json& slot = out[pointer];
    if (slot.is_null()) slot = {{"properties", json::object()}};
    slot["properties"][key] = std::move(property);
  };
  const json temperature = {{"$ref", "#/$defs/temperature"}};
  add("/$defs", "temperature",
      {{"description", "A temperature: an integer in 0.1 K (3.9.6) or a string such as \"110 degC\" or \"383.1 K\" (0 degC = "
                       "273.1 K as 3.9.6 scales it; at most " + dg::kelvin_string(list_keys::kTemperatureMax) + ")."},
       {"oneOf", json::array({json{{"type", "integer"}, {"minimum", 0}, {"maximum", list_keys::kTemperatureMax}},
                              json{{"type", "string"}, {"pattern", "^(-?[0-9]{1,5}(\\.[0-9]{1,3})? ?degC|[0-9]{1,5}(\\.[0-9]{1,3})? ?K)$"}},
                              json{{"type", "string"}, {"pattern", "^0[xX][0-9a-fA-F]{1,4}$"}}})}});
  add("/$defs", "a3_address", {{"description", "An A3 diagnosis address 1 .. " + std::to_string(dg::kDiagnosisAddressMax) + "."},
                                {"type", "string"}, {"pattern", input::word_string_pattern(1, dg::kDiagnosisAddressMax)}});
  add("/$defs/encoder/properties/sensors/properties", "test_values",
      {{"description", "By port address: the " + std::to_string(protocol::kTestValueBits) + "-bit test value the port sends (2.9)."},
       {"type", "object"}, {"propertyNames", {{"pattern", input::word_string_pattern(0, 0xFF)}}},
       {"additionalProperties", {{"oneOf", json::array({json{{"type", "integer"}, {"minimum", 0}, {"maximum", protocol::kTestValueMax}},
                                                        json{{"type", "string"}, {"pattern", "^(0[xX][0-9a-fA-F]{1," + std::to_string((protocol::kTestValueBits + 3) / 4) + "}|[0-9]{1," +
                                                                                  std::to_string(std::to_string(protocol::kTestValueMax).size()) + "})$"}}})}}}});
  add("/$defs/expect/properties/diagnosis/properties", "additional_sensors",
      {{"description", "By address 0 .. " + std::to_string(dg::kAdditionalSensorAddresses - 1) + ": the temperature last read."},
       {"type", "object"}, {"propertyNames", {{"pattern", input::word_string_pattern(0, dg::kAdditionalSensorAddresses - 1)}}},
       {"additionalProperties", temperature}});
  add("/$defs", "words", {{"type", "array"}, {"maxItems", protocol::kAreaWordsMax}, {"items", {{"$ref", "#/$defs/word"}}}});
  add("/properties", "bus",
      {{"description", "Further encoders on the same bus (2.10), each with its own transceiver at the encoder end."},
       {"type", "array"}, {"minItems", 1}, {"maxItems", list_keys::kBusEncodersMax}, {"items", {{"$ref", "#/$defs/encoder"}}}});
  add("/$defs/encoder/properties", "reference_marks",
      {{"description", "Incremental encoders (word 14): positions of the reference marks in measuring steps."},
       {"type", "array"}, {"minItems", 1}, {"maxItems", list_keys::kReferenceMarksMax},
       {"items", {{"type", "integer"}, {"minimum", 0}, {"maximum", slave::EncoderParams::kMaxPosition}}}});
  const json additional_sensors = {{"type", "array"}, {"maxItems", dg::kAdditionalSensorAddresses}, {"items", temperature}};
  const json valuation_numbers = {{"type", "array"}, {"minItems", dg::kValuationNumbers}, {"maxItems", dg::kValuationNumbers},
                                  {"items", {{"$ref", "#/$defs/byte"}}}};
  json described = additional_sensors;
  described["description"] = "By address 0 .. " + std::to_string(dg::kAdditionalSensorAddresses - 1) +
                             ", sent with a 115 K offset (3.9.6).";
  add("/$defs/encoder/properties/sensors/properties", "additional_sensors", described);
  described = valuation_numbers;
  described["description"] = "Valuation numbers 1 .. " + std::to_string(dg::kValuationNumbers) +
                             " (A3), sent as diagnosis where operating parameters word 3 activates them.";
  add("/$defs/encoder/properties/sensors/properties", "valuation_numbers", described);
  add("/$defs/event/properties/sensors/properties", "additional_sensors", additional_sensors);
  add("/$defs/event/properties/sensors/properties", "valuation_numbers", valuation_numbers);
  add("/$defs/encoder/properties/memory/properties", "section2_blocks",
      {{"type", "array"}, {"maxItems", protocol::kSection2BlocksMax}, {"items", {{"$ref", "#/$defs/words"}}}});
  add("/$defs/master/properties", "duty_cycle",
      {{"description", "HIGH share of the period."}, {"type", "number"},
       {"minimum", master::MasterParams::kHighPermilleMin / 1000.0}, {"maximum", master::MasterParams::kHighPermilleMax / 1000.0}});
  add("/$defs/master/properties/diagnostics/properties", "valuation_numbers",
      {{"description", "Valuation numbers to activate in operating parameters word 3 (default 1 .. " +
                           std::to_string(dg::kValuationNumbers) + "), as far as word 5 supports them."},
       {"type", "array"}, {"items", {{"type", "integer"}, {"minimum", 1}, {"maximum", dg::kValuationNumbers}}}});
  add("/$defs/frame_expectation/properties", "additional_data",
      {{"type", "array"}, {"maxItems", protocol::kAdditionalDataPerFrameMax},
       {"items", {{"$ref", "#/$defs/additional_data_expectation"}}}});
  add("/$defs/expect/properties/delay_measurement/properties", "max_error",
      {{"description", "A duration (" + sim::format_time_range(sim::Time::zero(), list_keys::kDelayErrorMax) + ") or \"T/8\"."},
       {"anyOf", json::array({json{{"const", "T/8"}}, json{{"$ref", "#/$defs/duration"}}})}});
  add("/$defs/expect/properties/memory/items/properties", "encoder",
      {{"description", "0: the encoder; k: the k-th of bus."}, {"type", "integer"}, {"minimum", 0},
       {"maximum", list_keys::kBusEncodersMax}});
}

}  // namespace

json parameter_schema() {
  json out = json::object();
  for_each_section([&](const auto& section, const auto& defaults) {
    json properties = json::object();
    for (const auto& row : section.rows) properties[std::string(row.key)] = property(row, defaults);
    json required = json::array();
    for (const auto& row : section.rows)
      if (row.required) required.push_back(std::string(row.key));
    // Two sections may fill one object (master.crc: the generator's rows and the check's).
    for (const auto pointer : {section.pointer, section.also_pointer}) {
      if (pointer.empty()) continue;
      json& slot = out[std::string(pointer)];
      if (slot.is_null()) slot = {{"properties", json::object()}, {"required", json::array()}};
      slot["properties"].update(properties);
      for (const auto& key : required) slot["required"].push_back(key);
    }
  });
  json events = json::object();
  for (const auto& row : event_trigger_parameters()) events[std::string(row.key)] = property(row, Event{});
  for (const auto& k : event_kinds())
    if (auto p = event_kind_schema(k)) events[std::string(k.key)] = *p;
  out["/$defs/event/properties"] = {{"properties", events}, {"required", json::array()}};
  add_operation_schema(out);
  add_list_key_schema(out);
  return out;
}

std::string parameter_tables_markdown() {
  std::string md;
  for_each_section([&](const auto& section, const auto& defaults) {
    md += (md.empty() ? "" : "\n") + std::string("## ") + std::string(section.title) + "\n\n" + table(section.rows, defaults);
  });
  return md + operation_tables_markdown() + event_tables_markdown();
}

}  // namespace endatsim::scenarios

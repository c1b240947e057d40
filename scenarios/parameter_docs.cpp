#include "endatsim/scenarios/parameter_docs.hpp"

#include <span>
#include <string_view>

#include "endatsim/checker/timing_checker.hpp"
#include "endatsim/line/line.hpp"
#include "endatsim/master/master.hpp"
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
std::string description(const sim::Parameter<Params>& row, const Params& defaults) {
  std::string d(row.help);
  if (!row.section.empty()) d += " D297403 " + std::string(row.section) + ".";
  const auto type = sim::type_of(row);
  if (type == ParameterType::Duration || type == ParameterType::Frequency) d += " Range: " + sim::range_text(row) + ".";
  if (row.required) return d + " Required.";
  return d + " Default: " + sim::value_text(row, defaults) + ".";
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
    case ParameterType::Word: p["$ref"] = row.max <= 0xFF ? "#/$defs/byte" : "#/$defs/word"; break;
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
         cell(sim::range_text(row)) + " | " + (row.required ? "required" : cell(sim::value_text(row, defaults))) + " | " +
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
};

template <class F>
void for_each_section(F&& f) {
  f(Section<line::LineParams>{"line", "/$defs/line/properties", line::line_parameters()}, line::LineParams{});
  f(Section<line::TransceiverParams>{"line.master_transceiver, line.encoder_transceiver", "/$defs/transceiver/properties",
                                     line::transceiver_parameters()},
    line::LineParams{}.master);
  f(Section<slave::EncoderParams>{"encoder", "/$defs/encoder/properties", slave::encoder_parameters()}, slave::EncoderParams{});
  f(Section<master::MasterParams>{"master", "/$defs/master/properties", master::master_parameters()}, master::MasterParams{});
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
  f(Section<master::DiagnosticsParams>{"master.diagnostics", "/$defs/master/properties/diagnostics/properties",
                                       master::diagnostics_parameters()},
    master::DiagnosticsParams{});
  f(Section<checker::CheckerParams>{"checker", "/$defs/checker/properties", checker::checker_parameters()},
    checker::CheckerParams{});
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
    out[std::string(section.pointer)] = {{"properties", properties}, {"required", required}};
  });
  return out;
}

std::string parameter_tables_markdown() {
  std::string md;
  for_each_section([&](const auto& section, const auto& defaults) {
    md += (md.empty() ? "" : "\n") + std::string("## ") + std::string(section.title) + "\n\n" + table(section.rows, defaults);
  });
  return md;
}

}  // namespace endatsim::scenarios

#include "endatsim/scenarios/parameter_docs.hpp"

#include <span>
#include <string_view>

#include "endatsim/sim/parameter.hpp"
#include "endatsim/slave/encoder_params.hpp"

namespace endatsim::scenarios {
namespace {

using nlohmann::json;
using sim::ParameterType;

std::string_view type_name(ParameterType t) {
  switch (t) {
    case ParameterType::Duration: return "duration";
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
  if (sim::type_of(row) == ParameterType::Duration) d += " Range: " + sim::range_text(row) + ".";
  return d + " Default: " + sim::value_text(row, defaults) + ".";
}

template <class Params>
json property(const sim::Parameter<Params>& row, const Params& defaults) {
  json p = {{"description", description(row, defaults)}};
  switch (sim::type_of(row)) {
    case ParameterType::Duration: p["$ref"] = "#/$defs/duration"; break;
    case ParameterType::Count:
      p["type"] = "integer";
      p["minimum"] = row.min;
      p["maximum"] = row.max;
      break;
    case ParameterType::Flag: p["type"] = "boolean"; break;
    case ParameterType::Word: p["$ref"] = "#/$defs/word"; break;
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
         cell(sim::range_text(row)) + " | " + cell(sim::value_text(row, defaults)) + " | " +
         (row.section.empty() ? "model" : std::string(row.section)) + " | " + cell(row.help) + " |\n";
  return t;
}

}  // namespace

json encoder_parameter_schema() {
  json properties = json::object();
  const slave::EncoderParams defaults;
  for (const auto& row : slave::encoder_parameters()) properties[std::string(row.key)] = property(row, defaults);
  return properties;
}

std::string parameter_tables_markdown() {
  return "## encoder\n\n" + table(slave::encoder_parameters(), slave::EncoderParams{});
}

}  // namespace endatsim::scenarios

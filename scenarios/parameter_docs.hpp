#pragma once
// What is generated from the models' parameter rows (sim/parameter.hpp): the JSON Schema's
// properties for the scalar keys of a scenario's "encoder" object, and the table of
// docs/parameters.md. Tests hold the schema file and the document to these.

#include <string>

#include <nlohmann/json.hpp>

namespace endatsim::scenarios {

// "$defs/encoder/properties" entries for every row of slave::encoder_parameters().
nlohmann::json encoder_parameter_schema();

// The Markdown table of docs/parameters.md: key, type, range, default, D297403 section, meaning.
std::string parameter_tables_markdown();

}  // namespace endatsim::scenarios

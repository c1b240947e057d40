#pragma once
// What is generated from the models' parameter rows (sim/parameter.hpp): the JSON Schema's
// properties for the scalar keys of a scenario's objects, and the tables of docs/parameters.md.
// Tests hold the schema file and the document to these.

#include <string>

#include <nlohmann/json.hpp>

namespace endatsim::scenarios {

// For each object with parameter rows, by the JSON pointer of its "properties" in
// schema/scenario.schema.json: {"properties": {key: property...}, "required": [keys...]}.
nlohmann::json parameter_schema();

// The Markdown tables of docs/parameters.md, one per object: key, type, range, default, D297403
// section, meaning.
std::string parameter_tables_markdown();

}  // namespace endatsim::scenarios

#pragma once
// The operations of a scenario's script as data: one row per "op" with what it does, the mode
// commands of its frames, the D297403 section it follows and the parameter rows
// (sim/parameter.hpp) of its scalar keys. The loader reads an operation through these rows, and the
// JSON Schema's properties of each operation and the script tables of docs/parameters.md are
// generated from them (scenarios/parameter_docs.hpp), so a key's range and default are written once.

#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "endatsim/master/operation.hpp"
#include "endatsim/sim/parameter.hpp"

namespace endatsim::scenarios {

struct OperationKindRow {
  // A key whose value has a type of its own (a mode command, an MRS code, an information code):
  // the loader reads it, its schema is written by hand, `text` is what the docs say of it.
  struct OtherKey {
    std::string_view key;
    bool required;
    std::string_view text;
  };
  std::string_view key;  // "write_parameter"
  master::Operation::Kind kind;
  std::string_view section;  // where D297403 describes it; "" for the model's own
  std::string_view help;
  std::span<const sim::Parameter<master::Operation>> fields;
  std::span<const OtherKey> other_keys;
  bool sends_frames;  // may carry "expect"
  // The mode command of the frames of an access named after the spec's procedures; with both,
  // "command_type" chooses: "2.1" `command`, "2.2" `command_22` (the access in the command
  // supplement of a 2.2 position frame).
  std::optional<protocol::ModeCommand> command = {}, command_22 = {};
  master::Operation defaults = {};
};

// "at", which every operation may have.
std::span<const sim::Parameter<master::Operation>> operation_common_parameters();
// Every operation, in the order the docs list them.
std::span<const OperationKindRow> operation_kinds();
// The row of an "op"; none for an unknown one.
const OperationKindRow* operation_kind(std::string_view key);

}  // namespace endatsim::scenarios

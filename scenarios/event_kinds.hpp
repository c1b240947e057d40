#pragma once
// The keys of a scenario's events as data: the trigger keys every event may have, and one row per
// kind of event with what it does, the D297403 section it rests on and the parameter rows
// (sim/parameter.hpp) of the keys its object takes. The loader reads an event through these rows,
// and the JSON Schema's event properties and the event tables of docs/parameters.md are generated
// from them (scenarios/parameter_docs.hpp), so a key's range is written once.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "endatsim/scenarios/scenario.hpp"
#include "endatsim/sim/parameter.hpp"

namespace endatsim::scenarios {

struct EventKindRow {
  // How the kind's value is written in a scenario.
  enum class Body : std::uint8_t {
    Object,  // an object whose keys are `fields`
    Value,   // the value of the one row of `fields` itself ("t_cal": "2 ms")
    Custom,  // an object of values with types of their own (a memory area, temperatures): the
             // loader reads it, its schema is written by hand and `fields_text` names its keys
  };
  std::string_view key;  // the event's key for the kind: "bit_flip"
  Event::Kind kind;
  Body body;
  std::string_view section;  // where D297403 describes what the kind disturbs; "" for none
  std::string_view help;     // what happens
  std::span<const sim::Parameter<Event>> fields;
  std::string_view fields_text = {};  // Body::Custom: its keys, as the docs list them
};

// When an event acts: "at", "frame", "clock", "offset".
std::span<const sim::Parameter<Event>> event_trigger_parameters();
// Every kind, in the order a message lists them.
std::span<const EventKindRow> event_kinds();
// "set_cable, bit_flip, ... or sensors".
std::string event_kind_list();

}  // namespace endatsim::scenarios

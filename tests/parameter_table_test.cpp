// The models' parameter rows (sim/parameter.hpp): the loader and the models take each key exactly
// within its range, the spec's ranges are the spec's numbers, and the schema and
// docs/parameters.md are what the rows generate.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "endatsim/checker/timing_checker.hpp"
#include "endatsim/input/parameter_input.hpp"
#include "endatsim/line/line.hpp"
#include "endatsim/master/master.hpp"
#include "endatsim/protocol/crc_parameters.hpp"
#include "endatsim/scenarios/event_kinds.hpp"
#include "endatsim/scenarios/list_keys.hpp"
#include "endatsim/scenarios/loader.hpp"
#include "endatsim/scenarios/operation_kinds.hpp"
#include "endatsim/scenarios/parameter_docs.hpp"
#include "endatsim/slave/encoder_params.hpp"

namespace endatsim {
namespace {

using nlohmann::json;
using Row = sim::Parameter<slave::EncoderParams>;
using sim::ParameterType;

std::string slurp(const std::string& relative) {
  std::ifstream in(std::string(ENDATSIM_SOURCE_DIR) + "/" + relative, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

const Row& row(std::string_view key) {
  for (const auto& r : slave::encoder_parameters())
    if (r.key == key) return r;
  throw std::logic_error("no row " + std::string(key));
}

// Reads `value` into default parameters through the row, as the loader does.
slave::EncoderParams read(const Row& r, const json& value) {
  const std::string file = "test.json";
  slave::EncoderParams p;
  input::read_parameter(input::Node(value, "encoder." + std::string(r.key), file), r, p);
  return p;
}

TEST(EncoderParameterTable, SpecRangesAreTheSpecsNumbers) {
  EXPECT_EQ(row("t_m").min, sim::us(10).count());
  EXPECT_EQ(row("t_m").max, sim::us(30).count());
  EXPECT_EQ(row("t_m_short").min, sim::ns(1250).count());
  EXPECT_EQ(row("t_m_short").max, sim::ns(3750).count());
  EXPECT_EQ(row("t_ac_read").max, sim::ms(12).count());
  EXPECT_EQ(row("t_ac_write").max, sim::ms(12).count());
  EXPECT_EQ(row("position_bits").max, 48);
  EXPECT_EQ(row("continuous_low_bits").max, 7);  // 2.3.1.1: "a maximum of 7 Low Bits"
  EXPECT_EQ(sim::range_text(row("t_m")), "10 .. 30 us");
  // 2.1.2: the delay measurement's clock and three measurements; 300 m of cable on request.
  EXPECT_EQ(master::DelayMeasurementParams{}.count, 3U);
  EXPECT_EQ(line::line_parameters()[0].max, 300);
}

TEST(EncoderParameterTable, ValidateNamesTheKeyAndTheRange) {
  slave::EncoderParams p;
  p.t_m = sim::ns(9999);
  try {
    p.validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "encoder t_m must be 10 .. 30 us (2.3.2), got 9.999 us");
  }
  p = {};
  p.supplement_ignore_clocks = 17;
  EXPECT_THROW(p.validate(), std::invalid_argument);
  p = {};
  p.t_st_max = sim::ns(999);
  EXPECT_THROW(p.validate(), std::invalid_argument);
}

TEST(EncoderParameterTable, ChoicesWordsAndFlagsReadAsNamed) {
  EXPECT_EQ(read(row("kind"), "touch_probe").kind, slave::EncoderKind::TouchProbe);
  EXPECT_EQ(read(row("version"), "2.1").version, protocol::EndatVersion::V2_1);
  EXPECT_EQ(read(row("type1_handling"), "no_start_bit").type1, slave::Type1Handling::NoStartBit);
  EXPECT_EQ(read(row("eib_activation"), "word14_write").eib_activation, slave::EibActivation::Word14Write);
  EXPECT_THROW((void)read(row("kind"), "rotary"), input::InputError);
  EXPECT_THROW((void)read(row("kind"), 1), input::InputError);
  EXPECT_EQ(read(row("error_sources"), "0xFFFF").error_sources, 0xFFFF);
  EXPECT_THROW((void)read(row("error_sources"), 65536), input::InputError);
  EXPECT_TRUE(read(row("error1"), true).error1);
  EXPECT_THROW((void)read(row("error1"), "yes"), input::InputError);
}

// Each object's rows: unique keys with help, defaults inside their ranges, and every duration,
// frequency, number and count taken by the loader at its bounds and refused one step beyond,
// with the key's path in the message.
template <class Params>
void check_rows(std::span<const sim::Parameter<Params>> rows, const Params& defaults, const std::string& object) {
  std::set<std::string_view> keys;
  for (const auto& r : rows) {
    SCOPED_TRACE(object + "." + std::string(r.key));
    EXPECT_TRUE(keys.insert(r.key).second) << "two rows";
    EXPECT_FALSE(r.help.empty());
    EXPECT_LE(r.min, r.max);
    EXPECT_FALSE(sim::out_of_range(r, defaults, object).has_value());
    const auto type = sim::type_of(r);
    if (type == ParameterType::Flag || type == ParameterType::Word || type == ParameterType::Choice) continue;
    const auto value = [&](std::int64_t v) -> json {
      if (type == ParameterType::Duration) return std::to_string(v) + " ps";
      if (type == ParameterType::Frequency) return std::to_string(v) + " Hz";
      return v;
    };
    const std::string file = "test.json";
    const auto read_at = [&](std::int64_t v) {
      Params p = defaults;
      const json j = value(v);
      input::read_parameter(input::Node(j, object + "." + std::string(r.key), file), r, p);
      return p;
    };
    for (const auto bound : {r.min, r.max}) EXPECT_FALSE(sim::out_of_range(r, read_at(bound), object).has_value());
    if (r.zero_allowed) {
      EXPECT_FALSE(sim::out_of_range(r, read_at(0), object).has_value());
    }
    for (const auto beyond : {r.min - 1, r.max + 1}) {
      try {
        (void)read_at(beyond);
        ADD_FAILURE() << "took " << beyond;
      } catch (const input::InputError& e) {
        EXPECT_NE(std::string(e.what()).find(object + "." + std::string(r.key)), std::string::npos) << e.what();
      }
    }
  }
}

TEST(ParameterTables, EveryObjectsNumbersAreTakenAtTheirBoundsAndRefusedOneStepBeyond) {
  check_rows(line::line_parameters(), line::LineParams{}, "line");
  check_rows(line::transceiver_parameters(), line::LineParams{}.encoder, "line.encoder_transceiver");
  check_rows(slave::encoder_parameters(), slave::EncoderParams{}, "encoder");
  check_rows(master::master_parameters(), master::MasterParams{}, "master");
  check_rows(master::power_on_parameters(), master::MasterParams::PowerOnSequence{}, "master.power_on");
  check_rows(master::delay_measurement_parameters(), master::DelayMeasurementParams{}, "master.delay_measurement");
  check_rows(master::careful_parameters(), master::CarefulMaster{}, "master.careful");
  check_rows(master::safety_parameters(), master::SafetyParams{}, "master.safety");
  check_rows(master::diagnostics_parameters(), master::DiagnosticsParams{}, "master.diagnostics");
  check_rows(checker::checker_parameters(), checker::CheckerParams{}, "checker");
  check_rows(slave::sensor_parameters(), slave::Sensors{}, "encoder.sensors");
  check_rows(slave::motion_parameters(), slave::MotionProfile{}, "encoder.motion");
  check_rows(protocol::crc_generator_parameters(), protocol::CrcConfig{}, "encoder.crc");
  check_rows(master::crc_check_parameters(), master::CrcCheck{}, "master.crc");
  check_rows(master::setpoint_parameters(), master::MotionSetpoint{}, "master.safety.setpoint");
}

// The objects inside "encoder" and "master" whose single values are rows: a scenario's keys land
// in the models' parameters, and a value beyond a row's range is refused with its path and range.
TEST(ParameterTables, SensorsMotionCrcAndSetpointAreReadThroughTheirRows) {
  const auto load = [](const json& encoder, const json& master) {
    json s = {{"name", "rows"},
              {"line", {{"cable_length_m", 10}}},
              {"encoder", {{"version", "2.2"}, {"position_bits", 25}}},
              {"master", {{"f_c", "2 MHz"}, {"position_bits", 25}}},
              {"script", json::array({{{"op", "read_position"}}})}};
    s["encoder"].update(encoder);
    s["master"].update(master);
    return scenarios::load_scenario_text(s.dump(), "rows.json");
  };
  const auto s = load({{"crc", {{"preset", "0x0F"}, {"final_inversion", false}}},
                       {"sensors", {{"commutation", 5}, {"timestamp_unit", "2 ns"}, {"position2_offset", -7}}},
                       {"motion", {{"start", 100}, {"counts_per_s", -3}}}},
                      {{"crc", {{"preset", 30}, {"table_fault_width", 31}, {"accept_any", true}}},
                       {"safety", {{"setpoint", {{"start", 5}, {"counts_per_s", 9}}}}}});
  EXPECT_EQ(s.encoder.crc, (protocol::CrcConfig{.preset = 0x0F, .final_inversion = false}));
  EXPECT_EQ(s.encoder.sensors.commutation, 5);
  EXPECT_EQ(s.encoder.sensors.timestamp_unit, sim::ns(2));
  EXPECT_EQ(s.encoder.sensors.position2_offset, -7);
  EXPECT_EQ(s.encoder.motion.start, 100U);
  EXPECT_EQ(s.encoder.motion.counts_per_s, -3);
  EXPECT_EQ(s.master.crc.generator.preset, 30);
  EXPECT_TRUE(s.master.crc.generator.final_inversion);
  EXPECT_EQ(s.master.crc.table_fault_width, 31U);
  EXPECT_TRUE(s.master.crc.accept_any);
  EXPECT_EQ(s.master.safety.setpoint.start, 5U);
  EXPECT_EQ(s.master.safety.setpoint.counts_per_s, 9);
  const auto message = [&](const json& encoder, const json& master) -> std::string {
    try {
      load(encoder, master);
    } catch (const std::exception& e) {
      return e.what();
    }
    return "accepted";
  };
  EXPECT_THAT(message({{"crc", {{"preset", 32}}}}, json::object()), ::testing::HasSubstr("/encoder/crc/preset"));
  EXPECT_THAT(message({{"crc", {{"preset", 32}}}}, json::object()), ::testing::HasSubstr("0 .. 31"));
  EXPECT_THAT(message({{"sensors", {{"commutation", 8}}}}, json::object()), ::testing::HasSubstr("0 .. 7"));
  EXPECT_THAT(message({{"sensors", {{"timestamp_unit", "2 ms"}}}}, json::object()), ::testing::HasSubstr("1 ns .. 1 ms"));
  EXPECT_THAT(message({{"motion", {{"start", std::int64_t{1} << 48}}}}, json::object()),
              ::testing::HasSubstr("/encoder/motion/start"));
  EXPECT_THAT(message(json::object(), {{"crc", {{"table_fault_width", 49}}}}), ::testing::HasSubstr("0 .. 48"));
  EXPECT_THAT(message(json::object(), {{"crc", {{"presett", 1}}}}), ::testing::HasSubstr("preset"));
  EXPECT_THAT(message(json::object(), {{"safety", {{"setpoint", {{"counts_per_s", "fast"}}}}}}),
              ::testing::HasSubstr("/master/safety/setpoint/counts_per_s"));
}

// The models refuse what the loader would never give them, naming object, key and range.
TEST(ParameterTables, ValidateNamesObjectKeyAndRange) {
  master::MasterParams m;
  m.careful.retries = 11;
  try {
    m.validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "master careful retries must be 0 .. 10, got 11");
  }
  m = {};
  m.f_c = sim::MHz(17);
  EXPECT_THROW(m.validate(), std::invalid_argument);
  line::LineParams l;
  l.cable_length_m = 300.5;
  try {
    l.validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "line cable_length_m must be 0 .. 300 m (2.1.2), got 300.5 m");
  }
  l = {};
  l.encoder.receiver_delay = sim::ns(1001);
  EXPECT_THROW(l.validate(), std::invalid_argument);
}

// 2.1.2: f_e is 0 (eight times f_c) or a counter clock of its own; what lies between is refused
// by the loader and the model alike, each naming the range.
TEST(ParameterTables, TheCounterClockIsZeroOrAtLeastOneMegahertz) {
  const auto rows = master::delay_measurement_parameters();
  const auto& f_e = *std::find_if(rows.begin(), rows.end(), [](const auto& r) { return r.key == "f_e"; });
  EXPECT_EQ(sim::range_text(f_e), "0 or 1 MHz .. 2 GHz");
  master::MasterParams m;
  for (const sim::Hertz ok : {sim::Hertz{0}, sim::MHz(1), sim::MHz(2000)}) {
    m.measurement.f_e = ok;
    EXPECT_NO_THROW(m.validate()) << ok;
  }
  m.measurement.f_e = sim::MHz(1) - 1;
  try {
    m.validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "master delay_measurement f_e must be 0 or 1 MHz .. 2 GHz (2.1.2), got 999.999 kHz");
  }
  const json half = "500 kHz";
  master::DelayMeasurementParams d;
  try {
    input::read_parameter(input::Node(half, "/master/delay_measurement/f_e", "s.json"), f_e, d);
    FAIL();
  } catch (const input::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("0 Hz or 1 MHz .. 2 GHz"), std::string::npos) << e.what();
  }
  const json zero = "0 Hz";
  input::read_parameter(input::Node(zero, "/master/delay_measurement/f_e", "s.json"), f_e, d);
  EXPECT_EQ(d.f_e, 0U);
}

// Every object with parameter rows: the schema holds exactly the properties the rows generate,
// and requires exactly the rows that are required; and the keys of lists and maps hold the
// properties generated from the loader's bounds (their objects' "required" is not generated).
TEST(ParameterTables, SchemaHoldsTheGeneratedProperties) {
  const auto schema = json::parse(slurp("schema/scenario.schema.json"));
  const auto generated = scenarios::parameter_schema();
  // The objects of the models, the events, and "op" and "at" and each operation of the script
  // (encoder.crc and master.crc share the generator's rows; master.crc adds the check's); then
  // the eight objects that hold only lists and maps with generated bounds ($defs, the top level,
  // encoder.memory, the sensors event, a frame's and the run's expectations, the diagnosis
  // expectation).
  ASSERT_EQ(generated.size(), 25U + scenarios::operation_kinds().size());
  for (const auto& [pointer, part] : generated.items()) {
    SCOPED_TRACE(pointer);
    const json::json_pointer at(pointer);
    ASSERT_TRUE(schema.contains(at));
    for (const auto& [key, property] : part["properties"].items()) {
      ASSERT_TRUE(schema[at].contains(key)) << key;
      EXPECT_EQ(schema[at][key], property)
          << key << ": schema/scenario.schema.json is out of date: regenerate with "
          << "`endatsim parameters --schema | tools/update_schema.py schema/scenario.schema.json`";
    }
    if (!part.contains("required")) continue;
    const auto required = schema[at.parent_pointer()].value("required", json::array());
    EXPECT_EQ(required, part["required"]);
  }
}

// A scenario with one operation (and one event, if given), loaded.
scenarios::Scenario load_with(const json& op, const json& event = nullptr) {
  json s = {{"name", "rows"},
            {"line", {{"cable_length_m", 10}}},
            {"encoder", {{"version", "2.2"}, {"position_bits", 25}}},
            {"master", {{"f_c", "2 MHz"}, {"position_bits", 25}}},
            {"script", {op}}};
  if (!event.is_null()) s["events"] = {event};
  return scenarios::load_scenario_text(s.dump(), "rows.json");
}

// The loader's message for it, or "accepted".
std::string load_message(const json& op, const json& event = nullptr) {
  try {
    load_with(op, event);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "accepted";
}

// A list key at its bound and one past it: the loader takes the one and refuses the other, naming
// the bound the schema states (both come from scenarios/list_keys.hpp).
using ::testing::HasSubstr;

std::string encoder_message(const json& encoder_keys) {
  json s = {{"name", "lists"},
            {"line", {{"cable_length_m", 10}}},
            {"encoder", {{"version", "2.2"}, {"position_bits", 25}}},
            {"master", {{"f_c", "2 MHz"}, {"position_bits", 25}}},
            {"script", {{{"op", "read_position"}}}}};
  s["encoder"].update(encoder_keys);
  try {
    scenarios::load_scenario_text(s.dump(), "lists.json");
  } catch (const std::exception& e) {
    return e.what();
  }
  return "accepted";
}

TEST(ListKeys, ReferenceMarksAreAcceptedUpToTheSchemasMaxItemsAndRefusedBeyond) {
  const auto schema = json::parse(slurp("schema/scenario.schema.json"));
  const auto max = schema["$defs"]["encoder"]["properties"]["reference_marks"]["maxItems"].get<std::size_t>();
  ASSERT_EQ(max, scenarios::list_keys::kReferenceMarksMax);
  json marks = json::array();
  for (std::size_t i = 0; i < max; ++i) marks.push_back(1000 * i);
  EXPECT_EQ(encoder_message({{"reference_marks", marks}}), "accepted");
  marks.push_back(1000 * max);
  EXPECT_THAT(encoder_message({{"reference_marks", marks}}),
              HasSubstr("/encoder/reference_marks: expected an array of 1 .. " + std::to_string(max) + " positions"));
}

TEST(ListKeys, ATemperatureIsAcceptedUpToTheSchemasMaximumAndRefusedBeyond) {
  const auto schema = json::parse(slurp("schema/scenario.schema.json"));
  const auto max = schema["$defs"]["temperature"]["oneOf"][0]["maximum"].get<unsigned>();
  ASSERT_EQ(max, scenarios::list_keys::kTemperatureMax);
  EXPECT_EQ(encoder_message({{"sensors", {{"temperature_1", max}}}}), "accepted");
  EXPECT_THAT(encoder_message({{"sensors", {{"temperature_1", max + 1}}}}),
              HasSubstr("/encoder/sensors/temperature_1: expected an integer 0 .. " + std::to_string(max)));
  EXPECT_EQ(encoder_message({{"sensors", {{"temperature_1", "6553.5 K"}}}}), "accepted");
  EXPECT_THAT(encoder_message({{"sensors", {{"temperature_1", "6553.6 K"}}}}), HasSubstr("(0 .. 6553.5 K)"));
}

// The event keys the schema knows are the rows' and no others: the trigger keys and one per kind,
// and its "exactly one kind" list names every kind once.
TEST(EventKinds, SchemaKnowsExactlyTheTriggerAndKindKeys) {
  const auto schema = json::parse(slurp("schema/scenario.schema.json"));
  const json& event = schema["$defs"]["event"];
  std::set<std::string> keys, expected, one_of;
  for (const auto& [key, property] : event["properties"].items()) keys.insert(key);
  for (const auto& row : scenarios::event_trigger_parameters()) expected.insert(std::string(row.key));
  for (const auto& kind : scenarios::event_kinds()) expected.insert(std::string(kind.key));
  EXPECT_EQ(keys, expected);
  for (const auto& alternative : event["allOf"][1]["oneOf"]) one_of.insert(alternative["required"][0].get<std::string>());
  std::set<std::string> kinds;
  for (const auto& kind : scenarios::event_kinds()) kinds.insert(std::string(kind.key));
  EXPECT_EQ(one_of, kinds);
  EXPECT_EQ(event["allOf"][1]["oneOf"].size(), scenarios::event_kinds().size());
}

// Every kind is one event kind of the model, and the rows of an object kind are its keys.
TEST(EventKinds, EachKindIsReadThroughItsRows) {
  std::set<scenarios::Event::Kind> kinds;
  for (const auto& kind : scenarios::event_kinds()) {
    SCOPED_TRACE(std::string(kind.key));
    EXPECT_TRUE(kinds.insert(kind.kind).second);
    EXPECT_EQ(kind.body == scenarios::EventKindRow::Body::Custom, kind.fields.empty());
    EXPECT_EQ(kind.body == scenarios::EventKindRow::Body::Custom, !kind.fields_text.empty());
  }
  EXPECT_EQ(kinds.size(), static_cast<std::size_t>(scenarios::Event::Kind::SensorValues) + 1);
  const auto load = [](const json& event) { return load_with({{"op", "read_position"}}, event).events.at(0); };
  const auto message = [](const json& event) { return load_message({{"op", "read_position"}}, event); };
  // A row's range and its default.
  EXPECT_EQ(load({{"at", "1 ms"}, {"glitch", {{"wire", "clock"}, {"end", "encoder"}, {"width", "5 ns"}}}}).width, sim::ns(5));
  const auto width = message({{"at", "1 ms"}, {"glitch", {{"wire", "clock"}, {"end", "encoder"}, {"width", "2 ms"}}}});
  EXPECT_NE(width.find("/events/0/glitch/width"), std::string::npos) << width;
  EXPECT_NE(width.find("1 ps .. 1 ms"), std::string::npos) << width;
  EXPECT_EQ(load({{"at", "1 ms"}, {"stuck", {{"wire", "data"}, {"end", "master"}, {"level", 1}}}}).duration, std::nullopt);
  const auto level = message({{"at", "1 ms"}, {"stuck", {{"wire", "data"}, {"end", "master"}, {"level", 2}}}});
  EXPECT_NE(level.find("/events/0/stuck/level: expected an integer 0 .. 1, got number 2"), std::string::npos) << level;
  // A value kind, and a key no row has.
  EXPECT_EQ(load({{"frame", 2}, {"t_cal", "3 ms"}}).t_cal, sim::ms(3));
  EXPECT_NE(message({{"at", "1 ms"}, {"slip", {{"steps", 3}, {"stepz", 1}}}}).find("/events/0/slip"), std::string::npos);
  // The list of kinds comes from the rows.
  const auto none = message({{"at", "1 ms"}});
  EXPECT_NE(none.find("/events/0: expected one of " + scenarios::event_kind_list()), std::string::npos) << none;
  EXPECT_EQ(scenarios::event_kind_list().substr(0, 20), "set_cable, bit_flip,");
  EXPECT_EQ(scenarios::event_kind_list().substr(scenarios::event_kind_list().size() - 11), " or sensors");
}

// The schema has one block per operation, in the rows' order (the generated properties are found
// by their index), and "op" allows exactly the rows' operations.
TEST(OperationKinds, SchemaHasOneBlockPerOperationInTheRowsOrder) {
  const auto schema = json::parse(slurp("schema/scenario.schema.json"));
  const json& operation = schema["$defs"]["operation"];
  ASSERT_EQ(operation["allOf"].size(), scenarios::operation_kinds().size());
  for (std::size_t i = 0; i < scenarios::operation_kinds().size(); ++i) {
    const auto& row = scenarios::operation_kinds()[i];
    SCOPED_TRACE(std::string(row.key));
    const json& block = operation["allOf"][i];
    EXPECT_EQ(block["if"]["properties"]["op"]["const"], std::string(row.key));
    // The keys the block allows: "op", "at", "expect" where the operation sends frames, its rows,
    // its other keys, and "command_type" where it has both a 2.1 and a 2.2 command.
    std::set<std::string> allowed{"op", "at"}, expected;
    for (const auto& [key, value] : block["then"]["properties"].items()) expected.insert(key);
    if (row.sends_frames) allowed.insert("expect");
    for (const auto& field : row.fields) allowed.insert(std::string(field.key));
    for (const auto& other : row.other_keys) allowed.insert(std::string(other.key));
    EXPECT_EQ(allowed, expected);
    EXPECT_EQ(row.command.has_value() && row.command_22.has_value(), allowed.count("command_type") == 1);
  }
}

// A key one operation has and another has not, a rule between keys, and an operation's own default.
TEST(OperationKinds, EachOperationIsReadThroughItsRow) {
  const auto load = [](const json& op) { return load_with(op).script.at(0); };
  const auto message = [](const json& op) { return load_message(op); };
  const auto await = load({{"op", "await_not_busy"}});
  EXPECT_EQ(await.count, 1000U);
  EXPECT_EQ(await.cycle, sim::us(50));
  EXPECT_EQ(load({{"op", "await_not_busy"}, {"max_polls", 7}}).count, 7U);
  const auto write = load({{"op", "write_parameter"}, {"address", 5}, {"value", "0x0002"}, {"command_type", "2.2"}});
  EXPECT_EQ(write.command, protocol::ModeCommand::EncoderSendPositionValuesAndReceiveParameter);
  EXPECT_EQ(write.parameter, 2U);
  EXPECT_EQ(load({{"op", "write_parameter"}, {"address", 5}, {"value", 2}}).command,
            protocol::ModeCommand::EncoderReceiveParameters);
  EXPECT_NE(message({{"op", "wait"}, {"duration", "1 ms"}, {"count", 2}}).find("/script/0"), std::string::npos);
  const auto payload = message({{"op", "frame"}, {"command", "encoder_send_position_values"}, {"address", 3}});
  EXPECT_NE(payload.find("/script/0/address: \"address\" needs a mode command with a payload"), std::string::npos) << payload;
  EXPECT_EQ(load({{"op", "frame"}, {"command", "encoder_receive_parameters"}, {"address", 3}, {"parameter", 9}}).parameter, 9U);
  const auto unknown = message({{"op", "read_postion"}});
  EXPECT_NE(unknown.find("\"read_position\""), std::string::npos) << unknown;
}

TEST(ParameterTables, DocsParametersIsTheGeneratedTable) {
  const std::string doc = slurp("docs/parameters.md");
  const std::string table = scenarios::parameter_tables_markdown();
  ASSERT_GE(doc.size(), table.size());
  EXPECT_EQ(doc.substr(doc.size() - table.size()), table)
      << "docs/parameters.md is out of date: regenerate its table with `endatsim parameters`";
}

}  // namespace
}  // namespace endatsim

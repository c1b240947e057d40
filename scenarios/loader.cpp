#include "endatsim/scenarios/loader.hpp"

#include "endatsim/input/json_input.hpp"
#include "endatsim/input/parameter_input.hpp"
#include "endatsim/input/suggest.hpp"
#include "endatsim/protocol/crc_parameters.hpp"
#include "endatsim/scenarios/bundled_profiles.hpp"
#include "endatsim/scenarios/event_kinds.hpp"
#include "endatsim/scenarios/list_keys.hpp"
#include "endatsim/scenarios/operation_kinds.hpp"
#include "endatsim/slave/profile.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <set>
#include <sstream>

namespace endatsim::scenarios {
namespace {
namespace dg = protocol::diagnosis;

using input::json;
using input::Node;
using input::Object;
using input::trimmed;

// A temperature in 0.1 K (3.9.6): an integer of 0.1 K steps, or a string "110 degC" / "383.1 K"
// (0 degC = 273.1 K, as 3.9.6 scales it).
std::uint16_t as_temperature(const Node& n) {
  const std::string what =
      "a temperature: an integer in 0.1 K (or a hex string) or a string such as \"110 degC\" or \"383.1 K\" (0 .. " +
      protocol::diagnosis::kelvin_string(list_keys::kTemperatureMax) + ")";
  if (!n.raw().is_string()) return static_cast<std::uint16_t>(n.as_uint(0, list_keys::kTemperatureMax));
  static const std::regex kTemperature(R"(^(-?[0-9]{1,5}(\.[0-9]{1,3})?) ?(K|degC)$)");
  std::smatch m;
  const std::string s = n.raw().get<std::string>();
  if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X'))
    return static_cast<std::uint16_t>(n.as_word(list_keys::kTemperatureMax));
  if (!std::regex_match(s, m, kTemperature) || (m[3].str() == "K" && s[0] == '-')) n.fail(what);  // no K below 0
  const double x = std::stod(m[1].str());
  const long tenth = m[3].str() == "degC" ? protocol::diagnosis::tenth_kelvin_of_celsius(x) : std::lround(x * 10.0);
  if (tenth < 0 || tenth > list_keys::kTemperatureMax) n.fail(what);
  return static_cast<std::uint16_t>(tenth);
}

// How often something happened: an exact count, or ">=N", "<=N", "N..M".
CountMatcher as_count(const Node& n) {
  const std::string what = "a count: an integer, or a string \">=N\", \"<=N\" or \"N..M\"";
  CountMatcher m;
  if (n.raw().is_number_unsigned() || (n.raw().is_number_integer() && n.raw().get<std::int64_t>() >= 0)) {
    m.min = m.max = n.raw().get<std::uint64_t>();
    m.text = std::to_string(m.min);
    return m;
  }
  if (!n.raw().is_string()) n.fail(what);
  const std::string s = n.raw().get<std::string>();
  const auto number = [&](const std::string& t) {
    if (t.empty() || t.size() > 18 || t.find_first_not_of("0123456789") != std::string::npos) n.fail(what);
    return std::stoull(t);
  };
  if (s.rfind(">=", 0) == 0) m.min = number(s.substr(2));
  else if (s.rfind("<=", 0) == 0) m.max = number(s.substr(2));
  else if (const auto dots = s.find(".."); dots != std::string::npos) {
    m.min = number(s.substr(0, dots));
    m.max = number(s.substr(dots + 2));
    if (m.min > m.max) n.fail(what + " with N <= M");
  } else {
    m.min = m.max = number(s);
  }
  m.text = s;
  return m;
}

template <class F>
void validated(const Node& n, F&& validate) {
  try {
    validate();
  } catch (const std::invalid_argument& e) {
    n.fail_raw(e.what());
  }
}

// An object whose keys are all parameter rows (sim/parameter.hpp).
template <class Params>
void read_object(const Node& n, std::span<const sim::Parameter<Params>> rows, Params& p) {
  Object o(n);
  input::read_parameters(o, rows, p);
  o.done();
}

void read_transceiver(const Node& n, line::TransceiverParams& t) { read_object(n, line::transceiver_parameters(), t); }

void read_line(const Node& n, line::LineParams& p) {
  Object o(n);
  input::read_parameters(o, line::line_parameters(), p);
  if (auto v = o.opt("master_transceiver")) read_transceiver(*v, p.master);
  if (auto v = o.opt("encoder_transceiver")) read_transceiver(*v, p.encoder);
  o.done();
  validated(n, [&] { p.validate(); });
}

std::vector<std::uint16_t> read_words(const Node& n, std::size_t max) {
  if (!n.raw().is_array() || n.raw().size() > max) n.fail("an array of at most " + std::to_string(max) + " words");
  std::vector<std::uint16_t> words;
  for (std::size_t i = 0; i < n.raw().size(); ++i)
    words.push_back(static_cast<std::uint16_t>(n.item(i).as_word(0xFFFF)));
  return words;
}

protocol::Information read_information(const Node& n) {
  const auto i = protocol::information_from_key(n.as_string());
  if (!i) n.fail("an information code of 2.3.5 such as \"temperature_1\"");
  return *i;
}

// What the sensors measure (appendix A3, 2.3.5.1): in the encoder's sensors and in a "sensors" event.
slave::SensorValues read_sensor_values(Object& o) {
  slave::SensorValues s;
  if (auto v = o.opt("temperature_1")) s.temperature1 = as_temperature(*v);
  if (auto v = o.opt("temperature_2")) s.temperature2 = as_temperature(*v);
  if (auto v = o.opt("additional_sensors")) {
    if (!v->raw().is_array() || v->raw().size() > dg::kAdditionalSensorAddresses)
      v->fail("an array of at most " + std::to_string(dg::kAdditionalSensorAddresses) + " temperatures (a 4-bit address, 2.3.5.1)");
    s.additional_sensors.emplace();
    for (std::size_t i = 0; i < v->raw().size(); ++i)
      s.additional_sensors->push_back(as_temperature(v->item(i)));
  }
  if (auto v = o.opt("valuation_numbers")) {
    if (!v->raw().is_array() || v->raw().size() != dg::kValuationNumbers)
      v->fail("an array of the " + std::to_string(dg::kValuationNumbers) + " valuation numbers (A3)");
    s.valuation_numbers.emplace();
    for (std::size_t i = 0; i < dg::kValuationNumbers; ++i)
      (*s.valuation_numbers)[i] =
          static_cast<std::uint8_t>(v->item(i).as_word(0xFF));
  }
  return s;
}

void read_sensors(const Node& n, slave::Sensors& s) {
  Object o(n);
  const slave::SensorValues values = read_sensor_values(o);
  if (values.temperature1) s.temperature1 = *values.temperature1;
  if (values.temperature2) s.temperature2 = *values.temperature2;
  if (values.additional_sensors) s.additional_sensors = *values.additional_sensors;
  if (values.valuation_numbers) s.valuation_numbers = *values.valuation_numbers;
  input::read_parameters(o, slave::sensor_parameters(), s);
  if (auto v = o.opt("system_data")) {
    if (!v->raw().is_object())
      v->fail("an object of A3 address (1 .. " + std::to_string(dg::kDiagnosisAddressMax) +
              ", not a valuation number's n + 16 k, n = 1 .. " + std::to_string(dg::kValuationNumbers) + ") -> 8-bit value");
    for (const auto& [address, value] : v->raw().items()) {
      const json key = address;
      const Node at(key, v->path() + "/" + address, n.file());
      const auto a = static_cast<std::uint8_t>(at.as_word(dg::kDiagnosisAddressMax));
      const auto decoded = dg::decode_diagnosis_address(a);
      if (!decoded || decoded->bit < dg::kValuationNumbers)
        at.fail("an A3 address 1 .. " + std::to_string(dg::kDiagnosisAddressMax) + " that is not a valuation number's (n + 16 k, n = 1 .. " +
                std::to_string(dg::kValuationNumbers) + ")");
      s.system_data[a] = static_cast<std::uint8_t>(Node(value, v->path() + "/" + address, n.file()).as_word(0xFF));
    }
  }
  if (auto v = o.opt("test_values")) {
    if (!v->raw().is_object()) v->fail("an object of port address -> " + std::to_string(protocol::kTestValueBits) + "-bit test value");
    for (const auto& [port, value] : v->raw().items()) {
      const json key = port;
      const auto a = static_cast<std::uint8_t>(Node(key, v->path() + "/" + port, n.file()).as_word(0xFF));
      s.test_values[a] = Node(value, v->path() + "/" + port, n.file()).as_word(protocol::kTestValueMax);
    }
  }
  if (auto v = o.opt("not_updatable")) {
    if (!v->raw().is_array()) v->fail("an array of information codes");
    for (std::size_t i = 0; i < v->raw().size(); ++i)
      s.not_updatable.push_back(read_information(v->item(i)));
  }
  o.done();
}

// Memory areas given as arrays of words replace those of the default image (3.1).
void read_memory(const Node& n, slave::EncoderParams& p) {
  slave::MemoryImage image = p.memory.value_or(slave::default_memory_image(p));
  slave::read_memory_areas(n, image, "words", [](const Node& words, std::optional<protocol::MemoryArea>) {
    return read_words(words, protocol::kAreaWordsMax);
  });
  p.memory = image;
}

void read_encoder(const Node& n, slave::EncoderParams& p) {
  Object o(n);
  // A profile first; the keys below refine it. A bare name is a bundled profile (profiles/),
  // anything with a slash or ".json" a file relative to the scenario.
  if (auto v = o.opt("profile")) {
    const std::string name = v->as_string();
    std::filesystem::path path = std::filesystem::path(n.file()).parent_path() / name;
    if (is_bundled_profile_name(name)) {
      try {
        path = bundled_profile(name);
      } catch (const std::runtime_error& e) {
        v->fail_raw(e.what());
      }
    }
    try {
      slave::load_profile(path.string()).apply(p);
    } catch (const slave::ProfileError& e) {
      v->fail_raw(std::string("cannot use the profile: ") + e.what());
    }
  }
  input::read_parameters(o, slave::encoder_parameters(), p);
  if (auto v = o.opt("crc")) read_object(*v, protocol::crc_generator_parameters(), p.crc);
  if (auto v = o.opt("reference_marks")) {
    if (!v->raw().is_array() || v->raw().empty() || v->raw().size() > list_keys::kReferenceMarksMax)
      v->fail("an array of 1 .. " + std::to_string(list_keys::kReferenceMarksMax) + " positions");
    p.reference_marks.clear();
    for (std::size_t i = 0; i < v->raw().size(); ++i)
      p.reference_marks.push_back(
          v->item(i).as_uint(0, slave::EncoderParams::kMaxPosition));
  }
  if (auto v = o.opt("sensors")) read_sensors(*v, p.sensors);
  if (auto v = o.opt("motion")) read_object(*v, slave::motion_parameters(), p.motion);
  // Last: the default image follows the parameters read above (word 13, t_m_short, version).
  if (auto v = o.opt("memory")) {
    read_memory(*v, p);
    validated(*v, [&] { p.validate(); });
  }
  o.done();
  validated(n, [&] { p.validate(); });
}

void read_safety(const Node& n, master::SafetyParams& p) {
  Object o(n);
  input::read_parameters(o, master::safety_parameters(), p);
  if (auto v = o.opt("setpoint")) read_object(*v, master::setpoint_parameters(), p.setpoint);
  o.done();
  validated(n, [&] { p.validate(); });
}

void read_diagnostics(const Node& n, master::DiagnosticsParams& p) {
  Object o(n);
  input::read_parameters(o, master::diagnostics_parameters(), p);
  if (auto v = o.opt("valuation_numbers")) {
    if (!v->raw().is_array())
      v->fail("an array of valuation numbers 1 .. " + std::to_string(dg::kValuationNumbers) + " to activate (3.6.3)");
    p.configuration &= dg::kSystemSpecificDataBit;
    for (std::size_t i = 0; i < v->raw().size(); ++i)  // valuation number n is bit n - 1 of word 3
      p.configuration |= static_cast<std::uint16_t>(1U << (v->item(i).as_uint(1, dg::kValuationNumbers) - 1));
  }
  if (auto v = o.opt("system_specific_data"))
    p.configuration = static_cast<std::uint16_t>((p.configuration & ~dg::kSystemSpecificDataBit) |
                                                 (v->as_bool() ? dg::kSystemSpecificDataBit : 0));
  o.done();
  validated(n, [&] { p.validate(); });
}

void read_master(const Node& n, master::MasterParams& p) {
  Object o(n);
  input::read_parameters(o, master::master_parameters(), p);
  if (auto v = o.opt("duty_cycle"))
    p.high_permille = static_cast<unsigned>(std::lround(
        v->as_number(master::MasterParams::kHighPermilleMin / 1000.0, master::MasterParams::kHighPermilleMax / 1000.0, "") *
        1000.0));
  if (auto v = o.opt("power_on")) read_object(*v, master::power_on_parameters(), p.power_on);
  if (auto v = o.opt("crc")) {
    Object c(*v);
    input::read_parameters(c, protocol::crc_generator_parameters(), p.crc.generator);
    input::read_parameters(c, master::crc_check_parameters(), p.crc);
    c.done();
  }
  if (auto v = o.opt("safety")) read_safety(*v, p.safety);
  if (auto v = o.opt("diagnostics")) read_diagnostics(*v, p.diagnostics);
  if (auto v = o.opt("careful")) read_object(*v, master::careful_parameters(), p.careful);
  if (auto v = o.opt("delay_measurement")) read_object(*v, master::delay_measurement_parameters(), p.measurement);
  o.done();
  validated(n, [&] { p.validate(); });
}

void read_checker(const Node& n, checker::CheckerParams& p) { read_object(n, checker::checker_parameters(), p); }

protocol::ModeCommand read_command(const Node& n) {
  const std::string key = n.as_string();
  const auto c = protocol::mode_command_from_key(key);
  if (!c) {
    std::string names;
    for (const auto& m : protocol::mode_commands()) names += (names.empty() ? "" : ", ") + std::string(m.key);
    n.fail("a mode command name (" + names + ")");
  }
  return *c;
}

std::uint8_t read_mode_bits(const Node& n) {
  const std::string s = n.as_string();
  if (s.size() != protocol::frame_position::kModeBits || s.find_first_not_of("01") != std::string::npos)
    n.fail("six mode bits such as \"000111\"");
  return static_cast<std::uint8_t>(std::stoul(s, nullptr, 2));
}

std::uint8_t read_byte(const Node& n) { return static_cast<std::uint8_t>(n.as_word(0xFF)); }
std::uint16_t read_word16(const Node& n) { return static_cast<std::uint16_t>(n.as_word(0xFFFF)); }

// 2.4.1 / 2.4.2.1: an MRS code as a number, a hex string or the name of a memory area.
std::uint8_t read_mrs(const Node& n) {
  if (n.raw().is_string()) {
    const std::string s = n.raw().get<std::string>();
    if (const auto a = protocol::memory_area_from_key(s)) return protocol::info(*a).mrs;
    if (s.rfind("0x", 0) != 0 && s.rfind("0X", 0) != 0) {
      std::string names;
      for (const auto& a : protocol::memory_areas()) names += (names.empty() ? "" : ", ") + std::string(a.key);
      n.fail("an MRS code such as \"0xA9\" or a memory area (" + names + ")");
    }
  }
  return read_byte(n);
}

// "2.1" (default) or "2.2": which type of mode command carries the access.
bool read_endat22(Object& o) {
  auto v = o.opt("command_type");
  return v && v->as_enum<bool>({{"2.1", false}, {"2.2", true}});
}

AdditionalDataExpectation read_additional_data_expectation(const Node& n) {
  Object o(n);
  AdditionalDataExpectation e;
  const Node code = o.req("information");
  const auto i = protocol::information_from_key(code.as_string());
  if (!i) {
    std::string names;
    for (const auto& c : protocol::information_codes()) names += (names.empty() ? "" : ", ") + std::string(c.key);
    code.fail("an information code (" + names + ")");
  }
  e.information = *i;
  if (auto v = o.opt("data")) e.data = read_word16(*v);
  if (auto v = o.opt("busy")) e.busy = v->as_bool();
  if (auto v = o.opt("rm")) e.rm = v->as_bool();
  o.done();
  return e;
}

// The frame outcomes by name, as the master reports them (master::kFrameOutcomes).
std::span<const std::string_view> outcome_names() {
  static const auto names = [] {
    std::array<std::string_view, master::kFrameOutcomes.size()> n{};
    for (std::size_t i = 0; i < n.size(); ++i) n[i] = master::to_string(master::kFrameOutcomes[i]);
    return n;
  }();
  return names;
}

std::string outcome_name(const Node& n) {
  const std::string text = n.as_string();
  for (auto name : outcome_names())
    if (name == text) return text;
  n.fail_choice(std::vector<std::string>(outcome_names().begin(), outcome_names().end()));
}

FrameExpectation read_frame_expectation(const Node& n) {
  Object o(n);
  FrameExpectation e;
  if (auto v = o.opt("outcome"))
    e.outcome = outcome_name(*v);
  if (auto v = o.opt("position")) e.position = v->as_uint(0, slave::EncoderParams::kMaxPosition);
  if (auto v = o.opt("error1")) e.error1 = v->as_bool();
  if (auto v = o.opt("echo_address")) e.echo_address = read_byte(*v);
  if (auto v = o.opt("echo_parameter")) e.echo_parameter = read_word16(*v);
  if (auto v = o.opt("test_value")) e.test_value = v->as_word(protocol::kTestValueMax);
  if (auto v = o.opt("additional_data")) {
    if (!v->raw().is_array() || v->raw().size() > protocol::kAdditionalDataPerFrameMax)
      v->fail("an array of at most " + std::to_string(protocol::kAdditionalDataPerFrameMax) + " additional data");
    std::vector<AdditionalDataExpectation> list;
    for (std::size_t i = 0; i < v->raw().size(); ++i)
      list.push_back(read_additional_data_expectation(v->item(i)));
    e.additional_data = list;
  }
  o.done();
  return e;
}

// The keys of an operation that its rows do not read (OperationKindRow::other_keys), and the
// rules between keys; `row.command` and `command_22` give the mode command of an access.
void read_other_keys(Object& o, const OperationKindRow& row, master::Operation& op) {
  const std::string_view name = row.key;
  if (row.command_22 && row.command) op.command = read_endat22(o) ? *row.command_22 : *row.command;
  else if (row.command) op.command = *row.command;
  else if (row.command_22) op.command = *row.command_22;
  if (name == "frame") {
    op.command = read_command(o.req("command"));
  } else if (name == "read_position" || name == "safety_startup") {
    if (auto v = o.opt("command")) op.command = read_command(*v);
    if (protocol::info(op.command).answer != protocol::AnswerFormat::Position)
      o.req("command").fail(name == "read_position" ? "a position command; use \"op\": \"frame\" for the others"
                                                    : "a position command for the start-up reads");
  } else if (name == "select_memory_area") {
    op.address = read_mrs(o.req("mrs"));
  } else if (name == "select_additional_data") {
    const Node code = o.req("additional_data");
    const std::string key = code.as_string();
    const auto i = protocol::information_from_key(key);
    if (key == "stop_1") op.address = protocol::kStopAdditionalData1;
    else if (key == "stop_2") op.address = protocol::kStopAdditionalData2;
    else if (i) op.address = protocol::selection_mrs(*i);
    else code.fail("an information code of 2.3.5 (e.g. temperature_1, memory_parameter_lsb) or stop_1 / stop_2");
  }
  if (name == "frame" || name == "read_position")
    if (auto v = o.opt("mode_bits")) op.mode_bits = read_mode_bits(*v);
}

// What one key allows only with another.
void check_key_rules(Object& o, const OperationKindRow& row, const master::Operation& op) {
  const auto& c = protocol::info(op.command);
  if (row.key == "frame" && c.payload_bits == 0 && !c.supplement)
    for (const char* key : {"address", "parameter"})
      if (auto v = o.opt(key)) v->fail_raw("\"" + std::string(key) + "\" needs a mode command with a payload or a command supplement");
  if (row.key == "select_memory_area" && op.command != protocol::ModeCommand::EncoderSendPositionValuesAndSelectionOfMemoryArea)
    if (auto v = o.opt("block")) v->fail_raw("a block address needs \"command_type\": \"2.2\" (2.4.2)");
  if (op.continuous_words > 0 && op.command != protocol::ModeCommand::EncoderSendPositionValues)
    o.req("continuous_words").fail_raw("a continuous clock is only possible with encoder_send_position_values (spec 2.3.1)");
}

// An operation through its row (scenarios/operation_kinds.hpp).
master::Operation read_operation(const Node& n, std::optional<FrameExpectation>& expect) {
  Object o(n);
  const Node kind = o.req("op");
  const OperationKindRow* row = kind.raw().is_string() ? operation_kind(kind.raw().get_ref<const std::string&>()) : nullptr;
  if (row == nullptr) {
    std::vector<std::string> names;
    for (const auto& r : operation_kinds()) names.emplace_back(r.key);
    kind.fail_choice(names);
  }
  master::Operation op = row->defaults;
  op.kind = row->kind;
  input::read_parameters(o, operation_common_parameters(), op);
  if (auto v = o.opt("expect")) {
    if (!row->sends_frames) v->fail_raw("\"expect\" needs an operation that sends frames");
    expect = read_frame_expectation(*v);
  }
  read_other_keys(o, *row, op);
  input::read_parameters(o, row->fields, op);
  check_key_rules(o, *row, op);
  o.done();
  return op;
}

void read_script(const Node& n, std::vector<master::Operation>& script,
                 std::vector<std::optional<FrameExpectation>>& expectations) {
  if (!n.raw().is_array() || n.raw().empty()) n.fail("a non-empty array of operations");
  std::optional<Time> last_at;
  for (std::size_t i = 0; i < n.raw().size(); ++i) {
    const Node item(n.raw()[i], n.path() + "/" + std::to_string(i), n.file());
    expectations.emplace_back();
    script.push_back(read_operation(item, expectations.back()));
    if (const auto at = script.back().at) {
      if (last_at && *at < *last_at)
        Node(item.raw()["at"], item.path() + "/at", n.file())
            .fail("a time not before the previous operation's \"at\" (" + sim::format_time(*last_at) + ")");
      last_at = at;
    }
  }
}

// ---- events --------------------------------------------------------------------------------

// The two kinds whose values have types of their own (EventKindRow::Body::Custom).
void read_custom_event(Object& f, Event& e) {
  if (e.kind == Event::Kind::CorruptWord) {
    const Node area = f.req("area");
    const auto a = protocol::memory_area_from_key(area.as_string());
    if (!a || *a == protocol::MemoryArea::AsynchronousPosition) area.fail("a memory area key such as \"manufacturer_3\"");
    e.selection.area = *a;
    if (auto v = f.opt("block")) e.selection.block = static_cast<std::uint8_t>(v->as_word(0xFF));
    e.address = static_cast<std::uint8_t>(f.req("address").as_word(0xFF));
    e.xor_mask = static_cast<std::uint16_t>(f.req("xor").as_word(0xFFFF));
    if (e.xor_mask == 0) f.req("xor").fail("a mask with at least one bit set");
  } else {
    e.sensors = read_sensor_values(f);
    if (!e.sensors.temperature1 && !e.sensors.temperature2 && !e.sensors.additional_sensors && !e.sensors.valuation_numbers)
      f.node().fail_raw("a sensors event sets at least one of temperature_1, temperature_2, additional_sensors, valuation_numbers");
  }
}

// An event through its rows (scenarios/event_kinds.hpp): the trigger, then exactly one kind.
Event read_event(const Node& item, const line::LineParams& line) {
  using Body = EventKindRow::Body;
  Object o(item);
  Event e;
  e.cable_delay_per_m = line.cable_delay_per_m;  // set_cable's default
  input::read_parameters(o, event_trigger_parameters(), e);
  if (e.at.has_value() == e.frame.has_value()) item.fail_raw("expected exactly one of \"at\" and \"frame\"");
  if (auto v = o.opt("clock"); v && !e.frame) v->fail_raw("\"clock\" needs \"frame\"");
  const EventKindRow* kind = nullptr;
  std::optional<Node> body;
  for (const auto& k : event_kinds()) {
    auto v = o.opt(std::string(k.key));
    if (!v) continue;
    if (body) v->fail_raw("one event does one thing: \"" + std::string(k.key) + "\" after another kind");
    body.emplace(*v);
    kind = &k;
  }
  if (!body) item.fail_raw("expected one of " + event_kind_list());
  e.kind = kind->kind;
  if (kind->body == Body::Value) {
    input::read_parameter(*body, kind->fields.front(), e);
  } else {
    Object f(*body);
    if (kind->body == Body::Object) input::read_parameters(f, kind->fields, e);
    else read_custom_event(f, e);
    f.done();
  }
  o.done();
  return e;
}

// What only the encoder's memory image can tell: the kind of encoder, the size of an area.
void check_event_against_encoder(const Event& e, const slave::EncoderParams& encoder, const Node& item) {
  if (e.kind == Event::Kind::ProbeTrigger && encoder.kind != slave::EncoderKind::TouchProbe)
    item.fail_raw("probe_trigger needs an encoder of kind \"touch_probe\" (word 14 type 5)");
  if (e.kind != Event::Kind::CorruptWord) return;
  const slave::MemoryImage image = encoder.memory.value_or(slave::default_memory_image(encoder));
  const std::vector<std::uint16_t>* words = nullptr;
  if (e.selection.area == protocol::MemoryArea::Section2) {
    if (e.selection.block < image.section2_blocks.size()) words = &image.section2_blocks[e.selection.block];
  } else if (const auto it = image.areas.find(e.selection.area); it != image.areas.end()) {
    words = &it->second;
  }
  const Node at(item.raw()["corrupt_word"], item.path() + "/corrupt_word", item.file());
  if (words == nullptr) at.fail_raw("the encoder has no memory area \"" + std::string(protocol::info(e.selection.area).key) + "\"" +
                                    (e.selection.area == protocol::MemoryArea::Section2 ? " block " + std::to_string(e.selection.block) : ""));
  if (e.address >= words->size())
    at.fail_raw("address " + std::to_string(e.address) + " is beyond the area's " + std::to_string(words->size()) + " words");
}

void read_events(const Node& n, const line::LineParams& line, std::vector<Event>& events) {
  if (!n.raw().is_array()) n.fail("an array of events");
  std::optional<Time> last_at;
  for (std::size_t i = 0; i < n.raw().size(); ++i) {
    const Node item(n.raw()[i], n.path() + "/" + std::to_string(i), n.file());
    Event e = read_event(item, line);
    if (e.at && last_at && *e.at < *last_at)
      Node(item.raw()["at"], item.path() + "/at", n.file())
          .fail("a time not before the previous event's (" + sim::format_time(*last_at) + ")");
    if (e.at) last_at = e.at;
    events.push_back(e);
  }
}

// `wildcard`: the map may also have kAnyOtherCheck ("*"), the count of everything not named.
void read_count_map(const Node& n, std::map<std::string, CountMatcher>& out, std::span<const std::string_view> allowed,
                    bool wildcard = false) {
  if (!n.raw().is_object()) n.fail("an object of counts");
  for (const auto& [key, value] : n.raw().items()) {
    const Node item(value, n.path() + "/" + key, n.file());
    bool ok = wildcard && key == kAnyOtherCheck;
    std::string names = wildcard ? std::string(kAnyOtherCheck) : std::string();
    std::vector<std::string> known;
    for (auto a : allowed) {
      ok = ok || a == key;
      names += (names.empty() ? "" : ", ") + std::string(a);
      known.emplace_back(a);
    }
    if (!ok)
      item.fail_raw("unknown name \"" + input::trimmed(key) + "\" (" + input::did_you_mean(key, known) +
                    "expected one of: " + names + ")");
    out[key] = as_count(item);
  }
}

// The names (to_string) of every value of an enum listed in kValues: the keys of a count map.
template <const auto& kValues>
std::span<const std::string_view> names_of() {
  static const std::vector<std::string_view> names = [] {
    std::vector<std::string_view> v;
    for (auto x : kValues) v.push_back(master::to_string(x));
    return v;
  }();
  return names;
}

// Keys that are A3 or additional-sensor addresses, each mapped through `value`.
template <class F>
void read_address_map(const Node& n, unsigned min_address, unsigned max_address, const std::string& what, F&& value) {
  if (!n.raw().is_object()) n.fail("an object of address -> " + what);
  for (const auto& [address, item] : n.raw().items()) {
    const json key = address;
    const Node at(key, n.path() + "/" + address, n.file());
    const auto a = static_cast<unsigned>(at.as_word(max_address));
    if (a < min_address) at.fail("an address " + std::to_string(min_address) + " .. " + std::to_string(max_address));
    value(a, Node(item, n.path() + "/" + address, n.file()));
  }
}

DiagnosisExpectation read_diagnosis_expectation(const Node& n) {
  Object o(n);
  DiagnosisExpectation e;
  if (auto v = o.opt("notes")) read_count_map(*v, e.notes, names_of<master::kDiagnosisNoteKinds>());
  if (auto v = o.opt("valuation_numbers"))
    read_address_map(*v, 1, dg::kDiagnosisAddressMax, "8-bit valuation number (A3)",
                     [&](unsigned a, const Node& x) { e.valuation_numbers[a] = static_cast<unsigned>(x.as_word(0xFF)); });
  if (auto v = o.opt("temperature_1")) e.temperature1 = as_temperature(*v);
  if (auto v = o.opt("temperature_2")) e.temperature2 = as_temperature(*v);
  if (auto v = o.opt("additional_sensors"))
    read_address_map(*v, 0, dg::kAdditionalSensorAddresses - 1, "temperature", [&](unsigned a, const Node& x) { e.additional_sensors[a] = as_temperature(x); });
  if (auto v = o.opt("configuration")) e.configuration = static_cast<std::uint16_t>(v->as_word(0xFFFF));
  if (auto v = o.opt("warnings")) e.warnings = static_cast<std::uint16_t>(v->as_word(0xFFFF));
  if (auto v = o.opt("ignored_addresses")) e.ignored_addresses = as_count(*v);
  o.done();
  return e;
}

void read_expect(const Node& n, Expectations& e) {
  Object o(n);
  if (auto v = o.opt("outcomes")) read_count_map(*v, e.outcomes, outcome_names());
  if (auto v = o.opt("positions_match_encoder")) e.positions_match_encoder = v->as_bool();
  if (auto v = o.opt("positions")) {
    if (!v->raw().is_array()) v->fail("an array of positions");
    std::vector<std::uint64_t> p;
    for (std::size_t i = 0; i < v->raw().size(); ++i)
      p.push_back(v->item(i).as_uint(0, slave::EncoderParams::kMaxPosition));
    e.positions = p;
  }
  if (auto v = o.opt("delay_measurement")) {
    Object d(*v);
    DelayExpectation de;
    if (auto s = d.opt("accepted")) de.accepted = s->as_bool();
    if (auto s = d.opt("max_error")) {
      if (s->raw().is_string() && s->raw().get<std::string>() == "T/8") de.max_error_is_eighth = true;
      else de.max_error = s->as_duration(Time::zero(), list_keys::kDelayErrorMax);
    }
    d.done();
    e.delay_measurement = de;
  }
  if (auto v = o.opt("violations")) read_count_map(*v, e.violations, checker::check::all(), true);
  if (auto v = o.opt("max_cycle_overruns")) e.max_cycle_overruns = v->as_uint(0, UINT64_MAX);
  if (auto v = o.opt("max_busy_timeouts")) e.max_busy_timeouts = v->as_uint(0, UINT64_MAX);
  if (auto v = o.opt("busy_timeouts")) e.busy_timeouts = as_count(*v);
  if (auto v = o.opt("checksum"))
    e.checksum_ok = v->as_enum<bool>({{"ok", true}, {"mismatch", false}});
  if (auto v = o.opt("retries")) e.retries = as_count(*v);
  if (auto v = o.opt("remeasurements")) e.remeasurements = as_count(*v);
  if (auto v = o.opt("startup")) {
    Object st(*v);
    StartupExpectation se;
    if (auto x = st.opt("completed")) se.completed = x->as_bool();
    if (auto x = st.opt("errors")) se.errors = read_word16(*x);
    if (auto x = st.opt("warnings")) se.warnings = read_word16(*x);
    if (auto x = st.opt("word13")) se.word13 = read_word16(*x);
    if (auto x = st.opt("word37")) se.word37 = read_word16(*x);
    st.done();
    e.startup = se;
  }
  if (auto v = o.opt("safety")) {
    Object sf(*v);
    SafetyExpectation se;
    if (auto x = sf.opt("findings")) read_count_map(*x, se.findings, names_of<master::kSafetyFunctions>());
    if (auto x = sf.opt("axis_released")) se.axis_released = x->as_bool();
    if (auto x = sf.opt("release_position_correct")) se.release_position_correct = x->as_bool();
    if (auto x = sf.opt("undetected_errors")) se.undetected_errors = as_count(*x);
    if (auto x = sf.opt("position_comparisons")) se.position_comparisons = as_count(*x);
    sf.done();
    e.safety = se;
  }
  if (auto v = o.opt("diagnosis")) e.diagnosis = read_diagnosis_expectation(*v);
  if (auto v = o.opt("memory")) {
    if (!v->raw().is_array()) v->fail("an array of {\"area\", \"address\", \"value\"}");
    for (std::size_t i = 0; i < v->raw().size(); ++i) {
      const Node item(v->raw()[i], v->path() + "/" + std::to_string(i), n.file());
      Object m(item);
      MemoryExpectation me;
      if (auto x = m.opt("encoder")) me.encoder = static_cast<std::size_t>(x->as_uint(0, list_keys::kBusEncodersMax));
      const Node area = m.req("area");
      const auto a = protocol::memory_area_from_key(area.as_string());
      if (!a) area.fail("a memory area name such as \"oem_1\"");
      me.area = *a;
      if (auto b = m.opt("block")) me.block = read_byte(*b);
      me.address = read_byte(m.req("address"));
      me.value = read_word16(m.req("value"));
      m.done();
      e.memory.push_back(me);
    }
  }
  o.done();
}

// A bench's events and expectations may only use what needs no master model: the HDL master's
// clock is not known before it runs, and the master's own findings are the HDL design's.
void check_bench_events(const Node& events) {
  if (!events.raw().is_array()) return;  // read_events says what is wrong
  for (std::size_t i = 0; i < events.raw().size(); ++i) {
    const Node e(events.raw()[i], events.path() + "/" + std::to_string(i), events.file());
    if (!e.raw().is_object() || (!e.raw().contains("bit_flip") && !e.raw().contains("random_bit_errors"))) continue;
    if (e.raw().contains("random_bit_errors"))
      Node(e.raw()["random_bit_errors"], e.path() + "/random_bit_errors", e.file())
          .fail_raw("random_bit_errors flips one period of the master's clock, which a bench does not know: use "
                    "bit_flip or glitch events with a width");
    const json& flip = e.raw()["bit_flip"];
    if (!flip.is_object() || !flip.contains("width"))
      Node(flip, e.path() + "/bit_flip", e.file())
          .fail_raw("a bench's bit_flip needs a \"width\" (one period of the HDL master's clock flips one bit)");
  }
}

void check_bench_expect(const Node& expect) {
  if (!expect.raw().is_object()) return;  // read_expect says what is wrong
  static const std::set<std::string> kBench{"positions_match_encoder", "positions", "violations"};
  for (const auto& [key, value] : expect.raw().items())
    if (kBench.count(key) == 0)
      Node(value, expect.path() + "/" + key, expect.file())
          .fail_raw("\"" + key + "\" needs the project's master model; a bench judges positions_match_encoder, "
                    "positions and violations");
}

Scenario read_scenario(const json& root, const std::string& file, ScenarioKind kind) {
  const Node top(root, "", file);
  Object o(top);
  const bool bench = kind == ScenarioKind::Bench;
  if (bench)
    for (const char* key : {"master", "script"})
      if (auto v = o.opt(key))
        v->fail_raw(std::string("a co-simulation bench has no \"") + key +
                    "\": the master and what it does are the HDL design's (remove \"master\" and \"script\")");
  Scenario s;
  s.file = file;
  s.name = o.req("name").as_string();
  if (s.name.empty() || s.name.find_first_of("/\\ \t\n") != std::string::npos ||
      std::any_of(s.name.begin(), s.name.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }))
    o.req("name").fail("a non-empty name without spaces, slashes or control characters");
  if (auto v = o.opt("description")) s.description = v->as_string();
  if (auto v = o.opt("$schema")) v->as_string();  // for editors (schema/scenario.schema.json); not used
  if (auto v = o.opt("field")) {
    Object f(*v);
    const auto text = [&f](const char* key) {
      const Node n = f.req(key);
      const std::string t = n.as_string();
      if (t.empty()) n.fail("a non-empty text");
      return t;
    };
    s.field = FieldNote{text("symptom"), text("cause"), text("spec"), text("asserts")};
    f.done();
  }
  if (auto v = o.opt("seed")) s.seed = v->as_uint(0, UINT64_MAX);
  if (auto v = o.opt("max_time")) s.max_time = v->as_duration(sim::us(1), Scenario::kMaxTime);
  if (auto v = o.opt("limits")) {
    Object l(*v);
    for (auto [key, field] : {std::pair{"kernel_events", &ScenarioLimits::kernel_events},
                              {"script_frames", &ScenarioLimits::script_frames},
                              {"events", &ScenarioLimits::events},
                              {"records", &ScenarioLimits::records}})
      if (auto x = l.opt(key)) s.limits.*field = x->as_uint(1, UINT64_MAX);
    l.done();
  }
  read_line(o.req("line"), s.line);
  if (auto v = o.opt("encoder")) read_encoder(*v, s.encoder);
  if (auto v = o.opt("bus")) {
    if (!v->raw().is_array() || v->raw().empty() || v->raw().size() > list_keys::kBusEncodersMax)
      v->fail("an array of 1 .. " + std::to_string(list_keys::kBusEncodersMax) + " further encoders on the bus (2.10)");
    for (std::size_t i = 0; i < v->raw().size(); ++i) {
      s.bus.emplace_back();
      read_encoder(v->item(i), s.bus.back());
    }
  }
  if (!bench) {
    read_master(o.req("master"), s.master);
    s.master.seed = s.seed;
    // Without a set-point of its own, the drive commands the motion the encoder makes.
    const json& m = root.at("master");
    if (!m.contains("safety") || !m["safety"].is_object() || !m["safety"].contains("setpoint"))
      s.master.safety.setpoint = {s.encoder.motion.start, s.encoder.motion.counts_per_s};
  }
  if (auto v = o.opt("checker")) read_checker(*v, s.checker);
  if (!bench) read_script(o.req("script"), s.script, s.operation_expectations);
  if (auto v = o.opt("events")) {
    if (bench) check_bench_events(*v);
    read_events(*v, s.line, s.events);
    for (std::size_t i = 0; i < s.events.size(); ++i)
      check_event_against_encoder(s.events[i], s.encoder, v->item(i));
  }
  if (auto v = o.opt("expect")) {
    if (bench) check_bench_expect(*v);
    read_expect(*v, s.expect);
  }
  o.done();
  return s;
}

}  // namespace

Scenario load_scenario_text(const std::string& text, const std::string& file_name, ScenarioKind kind) {
  try {
    return read_scenario(input::parse(text, file_name), file_name, kind);
  } catch (const input::InputError& e) {
    throw ScenarioError(e.what());
  } catch (const json::exception& e) {
    throw ScenarioError(file_name + ": " + e.what());
  }
}

Scenario load_scenario_file(const std::string& path, ScenarioKind kind) {
  std::string text;
  try {
    text = input::read_file(path, {"scenario", "a"});
  } catch (const input::InputError& e) {
    throw ScenarioError(e.what());
  }
  return load_scenario_text(text, path, kind);
}

}  // namespace endatsim::scenarios

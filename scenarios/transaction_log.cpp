#include "endatsim/scenarios/transaction_log.hpp"

#include <algorithm>
#include <bitset>
#include <cstdio>
#include <map>
#include <sstream>
#include <utility>
#include <variant>

#include "endatsim/protocol/frame.hpp"
#include "endatsim/scenarios/streamed_outputs.hpp"
#include "endatsim/sim/text.hpp"

namespace endatsim::scenarios {
namespace {

using nlohmann::ordered_json;


using sim::hex_0x;

// A field's value in the text log: a string as it is, a flag as 1 or 0, anything else as JSON.
void value_text(std::string& out, const JsonTokens& record, std::size_t value) {
  const JsonTokens::Token& t = record.at(value);
  if (t.kind == JsonTokens::Kind::String) out += t.text;
  else if (t.kind == JsonTokens::Kind::Bool) out += t.bits != 0 ? "1" : "0";
  else record.scalar(out, value);
}

// "name=value name=value", or "-" for none.
void fields_text(std::string& out, const JsonTokens& record, std::size_t object) {
  const auto members = record.members(object);
  if (members.empty()) out += '-';
  for (std::size_t i = 0; i < members.size(); ++i) {
    if (i > 0) out += ' ';
    out += record.at(members[i].first).text;
    out += '=';
    value_text(out, record, members[i].second);
  }
}

// The diagnosis values of 2.3.5.1 / A3 in words, without spaces: "3:20" (address: valuation
// number), "112.0degC", "1:72.5degC" (additional sensor address 1).
std::string decoded(const master::AdditionalDatum& d) {
  namespace dg = protocol::diagnosis;
  char buf[32];
  switch (d.information()) {
    case protocol::Information::Diagnosis:
      std::snprintf(buf, sizeof buf, "%u:%u", unsigned{protocol::datum_address(d.data)}, unsigned{protocol::datum_byte(d.data)});
      return buf;
    case protocol::Information::Temperature1:
    case protocol::Information::Temperature2:
      std::snprintf(buf, sizeof buf, "%.1fdegC", dg::celsius(d.data));
      return buf;
    case protocol::Information::AdditionalSensors: {
      const auto v = dg::decode_additional_sensor(d.data);
      std::snprintf(buf, sizeof buf, "%u:%.1fdegC", v.address, dg::celsius(v.tenth_kelvin));
      return buf;
    }
    default: return "";
  }
}

// Additional data (2.3.5), in wire order, by information code: the 16 data bits, and the status
// flags and CRC only when they say something. Each name once: the master reads the information
// code off the wire, so a frame with a misread status (an idle line after a power dip, a flipped
// bit) can carry one code twice; the later value then takes the earlier one's place, as in a JSON
// object.
std::vector<std::pair<std::string, std::variant<std::string, bool>>> additional_fields(
    const std::vector<master::AdditionalDatum>& data) {
  std::vector<std::pair<std::string, std::variant<std::string, bool>>> fields;
  const auto put = [&fields](std::string key, std::variant<std::string, bool> value) {
    const auto at = std::find_if(fields.begin(), fields.end(), [&key](const auto& f) { return f.first == key; });
    if (at != fields.end()) at->second = std::move(value);
    else fields.emplace_back(std::move(key), std::move(value));
  };
  for (const auto& d : data) {
    const std::string key(protocol::info(d.information()).key);
    put(key, hex_0x(d.data, 4));
    if (!d.crc_ok) put(key + ".crc_ok", false);
    if (d.busy()) put(key + ".busy", true);
    if ((d.status & protocol::AdditionalDataStatus::kWarning) != 0) put(key + ".warning", true);
    if ((d.status & protocol::AdditionalDataStatus::kReferenceMark) != 0) put(key + ".reference_mark", true);
    if (auto v = decoded(d); !v.empty()) put(key + ".decoded", std::move(v));
  }
  return fields;
}

}  // namespace

JsonTokens transaction_tokens(const master::FrameResult& f, std::span<const checker::Violation> violations,
                              const std::string* scenario) {
  JsonTokens t;
  t.begin_object();
  t.member("time_ps", f.start.count());
  t.member("time", sim::format_time(f.start));
  t.member("frame", f.index);
  t.member("word", f.word);
  t.member("command", protocol::info(f.command).key);
  t.member("mode_bits", protocol::mode_bits_string(f.mode_bits));

  t.key("sent").begin_object();
  t.member("mode_bits", protocol::mode_bits_string(f.mode_bits));
  t.member("f_c", sim::format_frequency(f.f_c));
  if (f.measurement) t.member("delay_measurement", true);
  if (f.compensated) t.member("t_d", sim::format_time(f.t_d_used));
  if (f.payload) {  // 2.1 parameter frames: address / MRS code / port, then 16 bits
    t.member("address", hex_0x(protocol::payload_address(*f.payload), 2));
    t.member("parameter", hex_0x(protocol::payload_parameter(*f.payload), 4));
  }
  if (f.supplement) {  // 2.2 command supplement
    t.member("supplement_address", hex_0x(protocol::payload_address(*f.supplement), 2));
    t.member("supplement_parameter", hex_0x(protocol::payload_parameter(*f.supplement), 4));
  }
  t.end_object();

  t.key("received").begin_object();
  const auto& command = protocol::info(f.command);
  const bool word = f.outcome == master::FrameOutcome::Ok || f.outcome == master::FrameOutcome::CrcError;
  if (f.start_bit_clock > 0) t.member("start_bit_clock", f.start_bit_clock);
  if (word) {
    switch (command.answer) {
      case protocol::AnswerFormat::Position:
        t.member("F1", f.error1 ? 1 : 0);
        if (command.version == protocol::EndatVersion::V2_2) t.member("F2", f.error2 ? 1 : 0);
        t.member("position", f.position);
        break;
      case protocol::AnswerFormat::TestValues:
        t.member("F1", f.error1 ? 1 : 0);
        t.member("test_value", hex_0x(f.test_value, 10));
        break;
      case protocol::AnswerFormat::Parameter:
        t.member("address", hex_0x(f.echo_address, 2));
        t.member("parameter", hex_0x(f.echo_parameter, 4));
        break;
    }
    t.member("crc", f.crc_received);
  }
  t.member("clocks", f.clocks);
  if (f.delay_count_time) t.member("delay_count", sim::format_time(*f.delay_count_time));
  t.end_object();

  if (word) t.member("crc_ok", f.outcome == master::FrameOutcome::Ok);
  else t.member("crc_ok", nullptr);
  if (word && f.outcome == master::FrameOutcome::CrcError) t.member("crc_expected", f.crc_expected);
  t.key("additional").begin_object();
  if (word)
    for (auto& [key, value] : additional_fields(f.additional_data)) {
      t.key(key);
      std::visit([&t](auto& v) { t.value(std::move(v)); }, value);
    }
  t.end_object();
  t.member("outcome", master::to_string(f.outcome));

  t.key("violations").begin_array();
  for (const auto& v : violations) {
    if (!v.frame || *v.frame != f.index) continue;
    t.begin_object();
    t.member("check", v.check);
    t.member("severity", checker::to_string(v.severity));
    if (!v.field.empty()) t.member("field", v.field);
    t.member("message", v.message);
    t.end_object();
  }
  t.end_array();
  if (scenario != nullptr) t.member("scenario", *scenario);
  t.end_object();
  return t;
}

ordered_json transaction_of(const master::FrameResult& f, std::span<const checker::Violation> violations) {
  return transaction_tokens(f, violations).ordered();
}

std::vector<ordered_json> transactions(const std::vector<master::FrameResult>& frames,
                                       const std::vector<checker::Violation>& violations) {
  std::vector<ordered_json> out;
  out.reserve(frames.size());
  for (const auto& f : frames) out.push_back(transaction_of(f, violations));
  return out;
}

std::string transaction_line(const JsonTokens& t) {
  constexpr std::size_t kRecord = 0;  // the record's object begins the tokens
  const auto field = [&](std::string_view key) { return t.at(t.find(kRecord, key)); };
  std::string s;
  const std::string& time = field("time").text;
  if (time.size() < 12) s.append(12 - time.size(), ' ');
  s += time;
  s += "  #" + std::to_string(field("frame").bits);
  if (field("word").bits > 0) s += "." + std::to_string(field("word").bits);
  s += "  " + field("command").text;
  s += "  sent: ";
  fields_text(s, t, t.find(kRecord, "sent"));
  s += "  received: ";
  fields_text(s, t, t.find(kRecord, "received"));
  if (const JsonTokens::Token& crc = field("crc_ok"); crc.kind == JsonTokens::Kind::Bool) {
    if (crc.bits != 0) {
      s += "  CRC ok";
    } else {
      s += "  CRC FAIL (expected ";
      t.scalar(s, t.find(kRecord, "crc_expected"));
      s += ")";
    }
  }
  if (const std::size_t additional = t.find(kRecord, "additional"); t.at(additional + 1).kind != JsonTokens::Kind::EndObject) {
    s += "  additional: ";
    fields_text(s, t, additional);
  }
  s += "  -> " + field("outcome").text;
  const std::size_t violations = t.find(kRecord, "violations");
  if (t.at(violations + 1).kind != JsonTokens::Kind::EndArray) {
    s += "  violations:";
    for (std::size_t v = violations + 1; t.at(v).kind != JsonTokens::Kind::EndArray; v = t.end_of(v))
      s += " " + t.at(t.find(v, "check")).text;
  }
  return s;
}

namespace {

// The log of the frames a result kept, as TransactionLogWriter writes it while a run goes.
std::string kept_log(const ScenarioResult& r, TransactionLogWriter::Format format) {
  std::map<std::uint64_t, std::vector<checker::Violation>> by_frame;  // in the order of their time
  for (const auto& v : r.violations)
    if (v.frame) by_frame[*v.frame].push_back(v);
  std::ostringstream out;
  TransactionLogWriter writer(out, format);
  writer.begin(r);
  for (const auto& f : r.frames) {
    const auto it = by_frame.find(f.index);
    writer.frame(r, f, it == by_frame.end() ? std::span<const checker::Violation>{} : std::span(it->second));
  }
  writer.end(r);
  return out.str();
}

}  // namespace

std::string transaction_log_text(const ScenarioResult& r) { return kept_log(r, TransactionLogWriter::Format::Text); }

std::string transaction_log_jsonl(const ScenarioResult& r) { return kept_log(r, TransactionLogWriter::Format::JsonLines); }

}  // namespace endatsim::scenarios

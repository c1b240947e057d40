#include "endatsim/scenarios/transaction_log.hpp"

#include <bitset>
#include <cstdio>
#include <map>
#include <sstream>

#include "endatsim/protocol/frame.hpp"
#include "endatsim/scenarios/streamed_outputs.hpp"
#include "endatsim/sim/text.hpp"

namespace endatsim::scenarios {
namespace {

using nlohmann::ordered_json;


using sim::hex_0x;

std::string value_text(const ordered_json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_boolean()) return v.get<bool>() ? "1" : "0";
  return v.dump();
}

std::string fields_text(const ordered_json& fields) {
  std::string s;
  for (const auto& [name, value] : fields.items()) s += (s.empty() ? "" : " ") + name + "=" + value_text(value);
  return s.empty() ? "-" : s;
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

}  // namespace

ordered_json transaction_of(const master::FrameResult& f, std::span<const checker::Violation> violations) {
  ordered_json t;
  t["time_ps"] = f.start.count();
  t["time"] = sim::format_time(f.start);
  t["frame"] = f.index;
  t["word"] = f.word;
  t["command"] = protocol::info(f.command).key;
  t["mode_bits"] = protocol::mode_bits_string(f.mode_bits);

  ordered_json sent = ordered_json::object();
  sent["mode_bits"] = protocol::mode_bits_string(f.mode_bits);
  sent["f_c"] = sim::format_frequency(f.f_c);
  if (f.measurement) sent["delay_measurement"] = true;
  if (f.compensated) sent["t_d"] = sim::format_time(f.t_d_used);
  if (f.payload) {  // 2.1 parameter frames: address / MRS code / port, then 16 bits
    sent["address"] = hex_0x(protocol::payload_address(*f.payload), 2);
    sent["parameter"] = hex_0x(protocol::payload_parameter(*f.payload), 4);
  }
  if (f.supplement) {  // 2.2 command supplement
    sent["supplement_address"] = hex_0x(protocol::payload_address(*f.supplement), 2);
    sent["supplement_parameter"] = hex_0x(protocol::payload_parameter(*f.supplement), 4);
  }
  t["sent"] = sent;

  ordered_json received = ordered_json::object();
  const auto& command = protocol::info(f.command);
  const bool word = f.outcome == master::FrameOutcome::Ok || f.outcome == master::FrameOutcome::CrcError;
  if (f.start_bit_clock > 0) received["start_bit_clock"] = f.start_bit_clock;
  if (word) {
    switch (command.answer) {
      case protocol::AnswerFormat::Position:
        received["F1"] = f.error1 ? 1 : 0;
        if (command.version == protocol::EndatVersion::V2_2) received["F2"] = f.error2 ? 1 : 0;
        received["position"] = f.position;
        break;
      case protocol::AnswerFormat::TestValues:
        received["F1"] = f.error1 ? 1 : 0;
        received["test_value"] = hex_0x(f.test_value, 10);
        break;
      case protocol::AnswerFormat::Parameter:
        received["address"] = hex_0x(f.echo_address, 2);
        received["parameter"] = hex_0x(f.echo_parameter, 4);
        break;
    }
    received["crc"] = f.crc_received;
  }
  received["clocks"] = f.clocks;
  if (f.delay_count_time) received["delay_count"] = sim::format_time(*f.delay_count_time);
  t["received"] = received;

  if (word) t["crc_ok"] = f.outcome == master::FrameOutcome::Ok;
  else t["crc_ok"] = nullptr;
  if (word && f.outcome == master::FrameOutcome::CrcError) t["crc_expected"] = f.crc_expected;
  // Additional data (2.3.5), in wire order, by information code: the 16 data bits, and the
  // status flags and CRC only when they say something.
  ordered_json additional = ordered_json::object();
  if (word)
    for (const auto& d : f.additional_data) {
      const std::string key(protocol::info(d.information()).key);
      additional[key] = hex_0x(d.data, 4);
      if (!d.crc_ok) additional[key + ".crc_ok"] = false;
      if (d.busy()) additional[key + ".busy"] = true;
      if ((d.status & protocol::AdditionalDataStatus::kWarning) != 0) additional[key + ".warning"] = true;
      if ((d.status & protocol::AdditionalDataStatus::kReferenceMark) != 0) additional[key + ".reference_mark"] = true;
      if (const auto v = decoded(d); !v.empty()) additional[key + ".decoded"] = v;
    }
  t["additional"] = additional;
  t["outcome"] = master::to_string(f.outcome);

  ordered_json vs = ordered_json::array();
  for (const auto& v : violations) {
    if (!v.frame || *v.frame != f.index) continue;
    ordered_json jv;
    jv["check"] = v.check;
    jv["severity"] = checker::to_string(v.severity);
    if (!v.field.empty()) jv["field"] = v.field;
    jv["message"] = v.message;
    vs.push_back(jv);
  }
  t["violations"] = vs;
  return t;
}

std::vector<ordered_json> transactions(const std::vector<master::FrameResult>& frames,
                                       const std::vector<checker::Violation>& violations) {
  std::vector<ordered_json> out;
  out.reserve(frames.size());
  for (const auto& f : frames) out.push_back(transaction_of(f, violations));
  return out;
}

std::string transaction_line(const ordered_json& t) {
  std::string time = t["time"].get<std::string>();
  if (time.size() < 12) time.insert(0, 12 - time.size(), ' ');
  std::string s = time + "  #" + std::to_string(t["frame"].get<std::uint64_t>());
  if (t["word"].get<unsigned>() > 0) s += "." + std::to_string(t["word"].get<unsigned>());
  s += "  " + t["command"].get<std::string>();
  s += "  sent: " + fields_text(t["sent"]);
  s += "  received: " + fields_text(t["received"]);
  if (t["crc_ok"].is_boolean())
    s += t["crc_ok"].get<bool>() ? "  CRC ok" : "  CRC FAIL (expected " + t["crc_expected"].dump() + ")";
  if (!t["additional"].empty()) s += "  additional: " + fields_text(t["additional"]);
  s += "  -> " + t["outcome"].get<std::string>();
  if (!t["violations"].empty()) {
    s += "  violations:";
    for (const auto& v : t["violations"]) s += " " + v["check"].get<std::string>();
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

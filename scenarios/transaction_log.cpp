#include "scenarios/transaction_log.hpp"

#include <bitset>

namespace endatsim::scenarios {
namespace {

using nlohmann::ordered_json;

std::string mode_bits_text(std::uint8_t bits) { return std::bitset<6>(bits).to_string(); }

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

}  // namespace

ordered_json transaction_of(const master::FrameResult& f, const std::vector<checker::Violation>& violations) {
  ordered_json t;
  t["time_ps"] = f.start.count();
  t["time"] = sim::format_time(f.start);
  t["frame"] = f.index;
  t["word"] = f.word;
  t["command"] = protocol::info(f.command).key;
  t["mode_bits"] = mode_bits_text(f.mode_bits);

  ordered_json sent = ordered_json::object();
  sent["mode_bits"] = mode_bits_text(f.mode_bits);
  sent["f_c"] = sim::format_frequency(f.f_c);
  if (f.measurement) sent["delay_measurement"] = true;
  if (f.compensated) sent["t_d"] = sim::format_time(f.t_d_used);
  t["sent"] = sent;

  ordered_json received = ordered_json::object();
  const bool word = f.outcome == master::FrameOutcome::Ok || f.outcome == master::FrameOutcome::CrcError;
  if (f.start_bit_clock > 0) received["start_bit_clock"] = f.start_bit_clock;
  if (word) {
    received["F1"] = f.error1 ? 1 : 0;
    if (protocol::info(f.command).version == protocol::EndatVersion::V2_2) received["F2"] = f.error2 ? 1 : 0;
    received["position"] = f.position;
    received["crc"] = f.crc_received;
  }
  received["clocks"] = f.clocks;
  if (f.delay_count_time) received["delay_count"] = sim::format_time(*f.delay_count_time);
  t["received"] = received;

  if (word) t["crc_ok"] = f.outcome == master::FrameOutcome::Ok;
  else t["crc_ok"] = nullptr;
  if (word && f.outcome == master::FrameOutcome::CrcError) t["crc_expected"] = f.crc_expected;
  // Additional data words (2.2 mode commands) join here, name -> value, when the master decodes them.
  t["additional"] = ordered_json::object();
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

std::string transaction_log_text(const ScenarioResult& r) {
  std::string s = "# " + r.name + " (" + r.file + ", seed " + std::to_string(r.seed) + "): " +
                  std::to_string(r.frames.size()) + " frames\n";
  for (const auto& t : transactions(r.frames, r.violations)) s += transaction_line(t) + "\n";
  return s;
}

std::string transaction_log_jsonl(const ScenarioResult& r) {
  std::string s;
  for (auto t : transactions(r.frames, r.violations)) {
    t["scenario"] = r.name;
    s += t.dump() + "\n";
  }
  return s;
}

}  // namespace endatsim::scenarios

#include "endatsim/scenarios/shard.hpp"
#include "endatsim/sim/text.hpp"

#include <charconv>
#include <stdexcept>

namespace endatsim::scenarios {
namespace {

using nlohmann::json;

using sim::whole_number;

const json& member(const json& j, const char* key, json::value_t type, const char* expected) {
  const auto it = j.find(key);
  const bool unsigned_ok = type == json::value_t::number_unsigned && it != j.end() && it->is_number_unsigned();
  if (it == j.end() || (it->type() != type && !unsigned_ok))
    throw std::invalid_argument(std::string("shard.") + key + ": expected " + expected);
  return *it;
}

std::size_t count_of(const json& j, const char* key) {
  return member(j, key, json::value_t::number_unsigned, "a whole number").get<std::size_t>();
}

}  // namespace

Shard parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  const auto k = slash == std::string::npos ? std::nullopt : whole_number(std::string_view(text).substr(0, slash));
  const auto n = slash == std::string::npos ? std::nullopt : whole_number(std::string_view(text).substr(slash + 1));
  if (!k || !n || *k == 0 || *n == 0 || *k > *n || *n > kMaxShards)
    throw std::invalid_argument("--shard expects K/N, shard K of N with 1 <= K <= N <= " + std::to_string(kMaxShards) +
                                " (2/4: the second of four), got '" + trimmed(text) + "'");
  return {*k, *n};
}

Slice slice_of(const Shard& shard, std::size_t total) {
  // In 128 bits: K x total cannot wrap whatever the list's length.
  const auto at = [&](std::size_t k) {
    return static_cast<std::size_t>(static_cast<unsigned __int128>(k) * total / shard.count);
  };
  return {at(shard.index - 1), at(shard.index)};
}

json to_json(const ShardMark& m) {
  json not_run = json::array();
  for (const auto& n : m.not_run) not_run.push_back({{"file", n.file}, {"name", n.name}, {"reason", n.reason}});
  return {{"endatsim", m.endatsim}, {"command", m.command},     {"index", m.shard.index}, {"count", m.shard.count},
          {"first", m.first},       {"items", m.items},         {"total", m.total},       {"inputs", m.inputs},
          {"options", m.options},   {"passed", m.passed},       {"incomplete", m.incomplete}, {"not_run", not_run}};
}

ShardMark shard_mark_of(const json& j) {
  if (!j.is_object()) throw std::invalid_argument("shard: expected an object");
  ShardMark m;
  m.endatsim = member(j, "endatsim", json::value_t::string, "a version string").get<std::string>();
  m.command = member(j, "command", json::value_t::string, "\"run\" or \"sweep\"").get<std::string>();
  if (m.command != "run" && m.command != "sweep") throw std::invalid_argument("shard.command: expected \"run\" or \"sweep\"");
  m.shard = {count_of(j, "index"), count_of(j, "count")};
  if (m.shard.index == 0 || m.shard.index > m.shard.count || m.shard.count > kMaxShards)
    throw std::invalid_argument("shard.index, shard.count: expected 1 <= index <= count <= " + std::to_string(kMaxShards));
  m.first = count_of(j, "first");
  m.items = count_of(j, "items");
  m.total = count_of(j, "total");
  const Slice slice = slice_of(m.shard, m.total);
  if (m.first != slice.begin || m.items != slice.end - slice.begin)
    throw std::invalid_argument("shard.first, shard.items: not the slice of shard " + std::to_string(m.shard.index) + "/" +
                                std::to_string(m.shard.count) + " of " + std::to_string(m.total));
  m.inputs = member(j, "inputs", m.command == "run" ? json::value_t::array : json::value_t::object,
                    m.command == "run" ? "the list of scenario files" : "the file and the grid");
  m.options = member(j, "options", json::value_t::object, "an object");
  m.passed = member(j, "passed", json::value_t::boolean, "true or false").get<bool>();
  m.incomplete = member(j, "incomplete", json::value_t::string, "a string").get<std::string>();
  for (const auto& n : member(j, "not_run", json::value_t::array, "an array")) {
    if (!n.is_object() || !n.contains("file") || !n.contains("name") || !n.contains("reason") || !n["file"].is_string() ||
        !n["name"].is_string() || !n["reason"].is_string())
      throw std::invalid_argument("shard.not_run: expected objects with the strings file, name and reason");
    m.not_run.push_back({n["file"].get<std::string>(), n["name"].get<std::string>(), n["reason"].get<std::string>()});
  }
  return m;
}

namespace {
std::string compact(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); }
}  // namespace

std::string text_log_mark(const ShardMark& mark) { return kTextLogMarkPrefix + compact(to_json(mark)) + "\n"; }

std::string json_lines_mark(const ShardMark& mark) { return compact(json{{"shard", to_json(mark)}}) + "\n"; }

std::string junit_mark(const ShardMark& mark) {
  std::string text;
  for (const char c : compact(to_json(mark))) text += c == '-' ? std::string("\\u002d") : std::string(1, c);
  return kJunitMarkPrefix + text + kJunitMarkSuffix + "\n";
}

json limits_json(const Limits& limits) {
  return {{"max_time_ps", limits.max_time ? json(limits.max_time->count()) : json(nullptr)},
          {"kernel_events", limits.kernel_events},
          {"script_frames", limits.script_frames},
          {"events", limits.events},
          {"records", limits.records}};
}

json run_shard_options(const std::optional<std::uint64_t>& seed, std::size_t examples, const Limits& limits,
                       JunitCases cases) {
  return {{"seed", seed ? json(*seed) : json(nullptr)},
          {"examples", examples},
          {"limits", limits_json(limits)},
          {"junit_cases", cases == JunitCases::Expectation ? "expectation" : "scenario"}};
}

}  // namespace endatsim::scenarios

#include "endatsim/scenarios/merge.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "endatsim/scenarios/interrupt.hpp"
#include "endatsim/scenarios/junit.hpp"
#include "endatsim/scenarios/loader.hpp"
#include "endatsim/scenarios/streamed_outputs.hpp"

namespace endatsim::scenarios {
namespace {

using nlohmann::json;

// A JUnit partial and a sweep's are read whole; nothing a shard writes comes near this.
constexpr std::uintmax_t kWholeFileLimit = 1ULL << 30;
// The mark's line (its list of scenario files) is read from the end of a log.
constexpr std::streamoff kMarkLineLimit = 64LL << 20;

// SIGINT or SIGTERM during a merge: it stops, and its outputs are never put in place.
void stop_if_interrupted(std::size_t line) {
  if (line % 4096 != 0) return;
  if (const int signal = interrupt_signal(); signal != 0)
    throw Interrupted("merge interrupted by " + signal_name(signal) + "; no output written", signal);
}

[[noreturn]] void fail(const std::string& path, const std::string& what) { throw MergeError(path + ": " + what); }

std::ifstream open(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) fail(path, "a directory, not a partial");
  // A FIFO would wait for a writer, a device never end.
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec)) fail(path, "not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, std::string("cannot open it: ") + std::strerror(errno));
  return in;
}

std::string whole_file(const std::string& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec && size > kWholeFileLimit) fail(path, "larger than 1 GiB; no partial of this kind is");
  auto in = open(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The last line (without its "\n"), read from the end.
std::string last_line(const std::string& path) {
  auto in = open(path);
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size <= 0) fail(path, "empty, not a partial");
  in.seekg(size - 1);
  if (in.get() != '\n') fail(path, "cut short: its last line has no end, where a partial ends with its shard's mark");
  std::streamoff begin = size - 1;
  std::string line;
  while (begin > 0 && size - begin < kMarkLineLimit) {
    const std::streamoff step = std::min<std::streamoff>(begin, 4096);
    std::string chunk(static_cast<std::size_t>(step), '\0');
    in.seekg(begin - step);
    in.read(chunk.data(), step);
    const auto newline = chunk.rfind('\n');
    if (newline != std::string::npos) return chunk.substr(newline + 1) + line;
    line = chunk + line;
    begin -= step;
  }
  if (begin > 0) fail(path, "its last line is longer than 64 MiB");
  return line;
}

ShardMark mark_of(const std::string& path, const json& j, const std::string& where) {
  try {
    return shard_mark_of(j);
  } catch (const std::invalid_argument& e) {
    fail(path, where + ": " + e.what());
  }
}

ShardMark mark_of_text(const std::string& path, const std::string& text, const std::string& where) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {  // syntax, invalid UTF-8, number overflow
    fail(path, where + ": not JSON (" + e.what() + ")");
  }
  return mark_of(path, j, where);
}

// Checks that a whole file is one JSON document without building it.
struct Validator {
  using number_integer_t = json::number_integer_t;
  using number_unsigned_t = json::number_unsigned_t;
  using number_float_t = json::number_float_t;
  using string_t = json::string_t;
  using binary_t = json::binary_t;
  bool null() { return true; }
  bool boolean(bool) { return true; }
  bool number_integer(number_integer_t) { return true; }
  bool number_unsigned(number_unsigned_t) { return true; }
  bool number_float(number_float_t, const string_t&) { return true; }
  bool string(string_t&) { return true; }
  bool binary(binary_t&) { return true; }
  bool start_object(std::size_t) { return true; }
  bool key(string_t&) { return true; }
  bool end_object() { return true; }
  bool start_array(std::size_t) { return true; }
  bool end_array() { return true; }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) {
    message = e.what();
    return false;
  }
  std::string message;
};

void require_json_document(const std::string& path) {
  auto in = open(path);
  Validator v;
  if (!json::sax_parse(in, &v, json::input_format_t::json, true)) fail(path, "not a JSON document: " + v.message);
}

// A run's results file as ResultsJsonWriter lays it out: "{", the version, "scenarios": [, each
// scenario's object from a line "    {" to a line "    }" (every line inside is indented
// deeper, and JSON strings hold no newline), "  ]," and the last members, "shard" among them.
class ResultsLines {
 public:
  explicit ResultsLines(const std::string& path) : path_(path), in_(open(path)) {
    if (!next() || line_ != "{" || !next() || !line_.starts_with("  \"endatsim\": ") || !next())
      fail(path_, "line " + std::to_string(number_) + ": expected a results file of endatsim run");
    if (line_ == "  \"scenarios\": [],") empty_ = true;
    else if (line_ != "  \"scenarios\": [")
      fail(path_, "line " + std::to_string(number_) + ": expected \"scenarios\" as the second key");
  }
  // True when the next scenario's object begins, false at the list's end.
  bool begins_scenario() {
    if (empty_ || ended_) return false;
    if (!next()) fail(path_, "cut short at line " + std::to_string(number_));
    if (line_ == "  ],") {
      ended_ = true;
      return false;
    }
    if (line_ != "    {") fail(path_, "line " + std::to_string(number_) + ": expected a scenario's object or the list's end");
    return true;
  }
  // Calls copy(line, last) for each line of the object begun, its closing "    }" last.
  template <class Copy>
  void scenario(const Copy& copy) {
    copy(line_, false);
    while (next()) {
      if (line_ == "    }" || line_ == "    },") {
        copy("    }", true);
        return;
      }
      copy(line_, false);
    }
    fail(path_, "cut short inside a scenario's object");
  }
  // The members after the list, as one object.
  json rest() {
    std::string text = "{";
    while (next()) text += line_ + "\n";
    try {
      return json::parse(text);
    } catch (const json::exception& e) {  // syntax, invalid UTF-8, number overflow
      fail(path_, std::string("the keys after \"scenarios\" are not JSON: ") + e.what());
    }
  }

 private:
  bool next() {
    if (!std::getline(in_, line_)) return false;
    stop_if_interrupted(++number_);
    return true;
  }
  std::string path_;
  std::ifstream in_;
  std::string line_;
  std::size_t number_ = 0;
  bool empty_ = false, ended_ = false;
};

Partial read_results(const std::string& path) {
  require_json_document(path);
  ResultsLines lines(path);
  std::size_t objects = 0;
  for (; lines.begins_scenario(); ++objects) lines.scenario([](const std::string&, bool) {});
  const json rest = lines.rest();
  if (!rest.contains("shard")) fail(path, "a results file of a whole run, not of a shard (no key \"shard\"); run with --shard K/N");
  Partial p{path, PartialKind::Results, mark_of(path, rest["shard"], "at /shard")};
  if (p.mark.command != "run") fail(path, "at /shard/command: a results file holds a run's shard, not a sweep's");
  if (objects + p.mark.not_run.size() != p.mark.items)
    fail(path, "holds " + std::to_string(objects) + " scenarios and " + std::to_string(p.mark.not_run.size()) +
                   " not run, where its shard has " + std::to_string(p.mark.items));
  return p;
}

// A JUnit partial's lines: the declaration, <testsuites>, <testsuite>, test cases, the closing
// tags and the mark.
struct JunitParts {
  std::size_t tests = 0, failures = 0, errors = 0;
  std::vector<std::string> cases, not_run;  // each test case's lines, with their "\n"
  ShardMark mark;
};

std::size_t attribute(const std::string& path, const std::string& line, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const auto at = line.find(key);
  std::size_t v = 0;
  const char* begin = line.data() + (at == std::string::npos ? 0 : at + key.size());
  const auto [end, ec] = std::from_chars(begin, line.data() + line.size(), v);
  if (at == std::string::npos || ec != std::errc{} || end == line.data() + line.size() || *end != '"')
    fail(path, "line 2: expected the attribute " + name + " with a whole number");
  return v;
}

JunitParts junit_parts(const std::string& path) {
  const std::string text = whole_file(path);
  std::vector<std::string> lines;
  for (std::size_t at = 0; at < text.size();) {
    const auto end = text.find('\n', at);
    if (end == std::string::npos) fail(path, "cut short: its last line has no end");
    lines.push_back(text.substr(at, end + 1 - at));
    at = end + 1;
  }
  const auto expect = [&](std::size_t i, bool ok, const char* what) {
    if (!ok) fail(path, "line " + std::to_string(i + 1) + ": expected " + what);
  };
  expect(0, lines.size() >= 6 && lines[0] == "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n", "a JUnit file of endatsim run");
  expect(1, lines[1].starts_with("<testsuites name=\"endatsim\" "), "<testsuites name=\"endatsim\" ...>");
  expect(2, lines[2].starts_with("  <testsuite name=\"endatsim\" "), "<testsuite name=\"endatsim\" ...>");
  JunitParts p;
  p.tests = attribute(path, lines[1], "tests");
  p.failures = attribute(path, lines[1], "failures");
  p.errors = attribute(path, lines[1], "errors");
  std::size_t i = 3;
  while (i < lines.size() && lines[i].starts_with("    <testcase ")) {
    std::string block = lines[i];
    const bool closed = lines[i].ends_with("/>\n");
    const bool not_run = !closed && i + 1 < lines.size() && lines[i + 1].starts_with("      <error type=\"not run\"");
    ++i;
    while (!closed && i < lines.size() && lines[i] != "    </testcase>\n") block += lines[i++];
    expect(i, closed || i < lines.size(), "</testcase>");
    if (!closed) block += lines[i++];
    (not_run ? p.not_run : p.cases).push_back(std::move(block));
  }
  expect(i, i + 3 == lines.size() && lines[i] == "  </testsuite>\n" && lines[i + 1] == "</testsuites>\n",
         "</testsuite>, </testsuites> and the shard's mark as the last lines");
  const std::string& mark = lines[i + 2];
  expect(i + 2, mark.starts_with(kJunitMarkPrefix) && mark.ends_with(std::string(kJunitMarkSuffix) + "\n"),
         "the shard's mark <!-- endatsim shard ... --> (a JUnit file of a whole run has none; run with --shard K/N)");
  const std::size_t prefix = std::strlen(kJunitMarkPrefix), suffix = std::strlen(kJunitMarkSuffix) + 1;
  p.mark = mark_of_text(path, mark.substr(prefix, mark.size() - prefix - suffix), "line " + std::to_string(i + 3));
  if (p.cases.size() + p.not_run.size() != p.tests)
    fail(path, "holds " + std::to_string(p.cases.size() + p.not_run.size()) + " test cases where its tests=\"" +
                   std::to_string(p.tests) + "\" says");
  return p;
}

Partial read_log(const std::string& path, PartialKind kind) {
  const std::string line = last_line(path);
  if (kind == PartialKind::Log) {
    if (!line.starts_with(kTextLogMarkPrefix))
      fail(path, "its last line is not the shard's mark \"# shard {...}\" (a log of a whole run has none; run with --shard K/N)");
    return {path, kind, mark_of_text(path, line.substr(std::strlen(kTextLogMarkPrefix)), "its last line")};
  }
  json j;
  try {
    j = json::parse(line);
  } catch (const json::exception&) {
    fail(path, "its last line is not the shard's mark {\"shard\": {...}} (a log of a whole run has none; run with --shard K/N)");
  }
  if (!j.is_object() || j.size() != 1 || !j.contains("shard"))
    fail(path, "its last line is not the shard's mark {\"shard\": {...}} (a log of a whole run has none; run with --shard K/N)");
  return {path, kind, mark_of(path, j["shard"], "its last line")};
}

// A sweep's partial, read whole and checked key by key.
const json& key_of(const std::string& path, const json& j, const std::string& where, const char* key,
                   bool (json::*is)() const noexcept, const char* expected) {
  const auto it = j.find(key);
  if (it == j.end() || !((*it).*is)()) fail(path, "at " + where + "/" + key + ": expected " + expected);
  return *it;
}

SweepPoint point_of(const std::string& path, const json& j, const std::string& where) {
  if (!j.is_object()) fail(path, "at " + where + ": expected a point's object");
  SweepPoint p;
  p.values = key_of(path, j, where, "values", &json::is_array, "the grid values").get<std::vector<json>>();
  p.clean = key_of(path, j, where, "clean", &json::is_boolean, "true or false").get<bool>();
  p.expectations_passed = key_of(path, j, where, "expectations_passed", &json::is_boolean, "true or false").get<bool>();
  p.ok = key_of(path, j, where, "ok", &json::is_number_unsigned, "a whole number").get<std::uint64_t>();
  p.crc_error = key_of(path, j, where, "crc_error", &json::is_number_unsigned, "a whole number").get<std::uint64_t>();
  p.other = key_of(path, j, where, "other", &json::is_number_unsigned, "a whole number").get<std::uint64_t>();
  p.violations = key_of(path, j, where, "violations", &json::is_number_unsigned, "a whole number").get<std::uint64_t>();
  for (const auto& c : key_of(path, j, where, "checks", &json::is_array, "the checks' names")) {
    if (!c.is_string()) fail(path, "at " + where + "/checks: expected the checks' names");
    p.checks.push_back(c.get<std::string>());
  }
  if (j.contains("incomplete"))
    p.incomplete = key_of(path, j, where, "incomplete", &json::is_string, "a string").get<std::string>();
  return p;
}

std::vector<GridAxis> grid_of(const std::string& path, const json& inputs) {
  std::vector<GridAxis> grid;
  const json& axes = key_of(path, inputs, "/shard/inputs", "grid", &json::is_array, "the grid's axes");
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const std::string where = "/shard/inputs/grid/" + std::to_string(a);
    if (!axes[a].is_object()) fail(path, "at " + where + ": expected {\"pointer\", \"values\"}");
    grid.push_back({key_of(path, axes[a], where, "pointer", &json::is_string, "a JSON pointer").get<std::string>(),
                    key_of(path, axes[a], where, "values", &json::is_array, "the axis's values").get<std::vector<json>>()});
  }
  return grid;
}

Partial read_sweep(const std::string& path, const json& j) {
  if (!j.contains("shard")) fail(path, "a sweep's results of the whole grid, not of a shard (no key \"shard\"); sweep with --shard K/N");
  Partial p{path, PartialKind::Sweep, mark_of(path, j["shard"], "at /shard")};
  if (p.mark.command != "sweep") fail(path, "at /shard/command: a sweep's file holds a sweep's shard");
  (void)key_of(path, p.mark.inputs, "/shard/inputs", "file", &json::is_string, "the scenario file");
  (void)grid_of(path, p.mark.inputs);
  const auto& points = key_of(path, j, "", "points", &json::is_array, "the grid points");
  if (points.size() != p.mark.items)
    fail(path, "holds " + std::to_string(points.size()) + " points where its shard has " + std::to_string(p.mark.items));
  return p;
}

std::string shard_name(const Partial& p) {
  return "shard " + std::to_string(p.mark.shard.index) + "/" + std::to_string(p.mark.shard.count);
}

}  // namespace

const char* option_of(PartialKind kind) {
  switch (kind) {
    case PartialKind::Results: return "--json";
    case PartialKind::Junit: return "--junit";
    case PartialKind::Log: return "--log";
    case PartialKind::LogJson: return "--log-json";
    case PartialKind::Sweep: return "--json";
  }
  return "?";
}

Partial read_partial(const std::string& path) {
  std::string first;
  {
    auto in = open(path);
    std::getline(in, first);
    if (in.bad()) fail(path, std::string("cannot read it: ") + std::strerror(errno));
  }
  if (first.starts_with("<?xml")) {
    auto parts = junit_parts(path);
    if (parts.mark.command != "run") fail(path, "the mark names a sweep's shard in a JUnit file");
    return {path, PartialKind::Junit, parts.mark};
  }
  if (first == "{") {
    std::string second, third;
    {
      auto in = open(path);
      std::getline(in, first);
      std::getline(in, second);
      std::getline(in, third);
    }
    if (third.starts_with("  \"scenarios\": ")) return read_results(path);
    const std::string text = whole_file(path);
    json j;
    try {
      j = json::parse(text);
    } catch (const json::exception& e) {  // syntax, invalid UTF-8, number overflow
      fail(path, std::string("not a JSON document: ") + e.what());
    }
    return read_sweep(path, j);
  }
  if (first.starts_with("# ")) return read_log(path, PartialKind::Log);
  if (first.starts_with("{")) return read_log(path, PartialKind::LogJson);
  fail(path, "not a partial of endatsim run or sweep --shard K/N: expected its --json, --junit, --log or --log-json file");
}

std::map<PartialKind, std::vector<Partial>> group_partials(const std::vector<Partial>& partials, const std::string& version) {
  if (partials.empty()) throw MergeError("no partial given");
  const Partial& first = partials.front();
  for (const auto& p : partials) {
    if (p.mark.endatsim != version)
      fail(p.path, "written by endatsim " + p.mark.endatsim + "; this is " + version + ": merge with the version that ran the shards");
    const std::string against = " than " + first.path + " (" + shard_name(first) + ")";
    if (p.mark.command != first.mark.command) fail(p.path, "a " + p.mark.command + "'s shard, not a " + first.mark.command + "'s like " + first.path);
    if (p.mark.shard.count != first.mark.shard.count) fail(p.path, "one of " + std::to_string(p.mark.shard.count) + " shards, not of " + std::to_string(first.mark.shard.count) + " like " + first.path);
    if (p.mark.inputs != first.mark.inputs || p.mark.total != first.mark.total)
      fail(p.path, std::string(first.mark.command == "run" ? "ran other scenario files" : "swept another file or grid") + against);
    if (p.mark.options != first.mark.options)
      fail(p.path, "ran with other options (" + p.mark.options.dump() + ")" + against + " (" + first.mark.options.dump() + ")");
  }
  std::map<PartialKind, std::vector<Partial>> by_kind;
  for (const auto& p : partials) by_kind[p.kind].push_back(p);
  for (auto& [kind, list] : by_kind)
    std::stable_sort(list.begin(), list.end(), [](const Partial& a, const Partial& b) { return a.mark.shard.index < b.mark.shard.index; });
  return by_kind;
}

void require_every_shard(const std::vector<Partial>& shards, const std::string& option) {
  if (shards.empty()) throw MergeError(option + ": no partial of this kind given");
  const std::size_t n = shards.front().mark.shard.count;
  std::vector<const Partial*> seen(n + 1, nullptr);
  for (const auto& p : shards) {
    auto& slot = seen[p.mark.shard.index];
    if (slot != nullptr) fail(p.path, "is the " + option + " partial of " + shard_name(p) + ", and so is " + slot->path);
    slot = &p;
  }
  std::string missing;
  std::size_t count = 0;
  for (std::size_t k = 1; k <= n; ++k)
    if (seen[k] == nullptr && count++ < 10) missing += (missing.empty() ? "" : ", ") + std::to_string(k);
  if (count != 0)
    throw MergeError(option + ": " + std::to_string(count) + " of " + std::to_string(n) + " shards missing (" + missing +
                     (count > 10 ? ", ..." : "") + "); give every shard's partial");
}

RunVerdict run_verdict(const std::vector<Partial>& shards) {
  RunVerdict v;
  for (const auto& p : shards) {
    v.passed = v.passed && p.mark.passed;
    if (v.incomplete.empty()) v.incomplete = p.mark.incomplete;
    v.not_run.insert(v.not_run.end(), p.mark.not_run.begin(), p.mark.not_run.end());
    v.scenarios = p.mark.total;
  }
  return v;
}

void merge_results_json(const std::vector<Partial>& shards, std::ostream& out) {
  ResultsJsonWriter writer(out, shards.front().mark.endatsim);
  for (const auto& p : shards) {
    ResultsLines lines(p.path);
    while (lines.begins_scenario())
      writer.copy_scenario([&](std::ostream& o) {
        lines.scenario([&](const std::string& line, bool last) { o << line << (last ? "" : "\n"); });
      });
  }
  const auto v = run_verdict(shards);
  std::vector<std::string> files;
  for (const auto& n : v.not_run) files.push_back(n.file);
  writer.finish(v.passed, v.incomplete, files);
}

void merge_junit(const std::vector<Partial>& shards, std::ostream& out) {
  std::size_t tests = 0, failures = 0, errors = 0;
  std::vector<JunitParts> parts;
  for (const auto& p : shards) {
    parts.push_back(junit_parts(p.path));
    tests += parts.back().tests;
    failures += parts.back().failures;
    errors += parts.back().errors;
  }
  out << junit_head("endatsim", tests, failures, errors);
  for (const auto& p : parts)
    for (const auto& c : p.cases) out << c;
  for (const auto& p : parts)
    for (const auto& c : p.not_run) out << c;
  out << junit_tail();
}

void merge_log(const std::vector<Partial>& shards, std::ostream& out) {
  for (const auto& p : shards) {
    // Held back: the shard's own "# incomplete" lines and its mark, which the whole run's end replaces.
    const std::size_t held = 1 + (p.mark.incomplete.empty() ? 0 : 1 + p.mark.not_run.size());
    auto in = open(p.path);
    std::deque<std::string> back;
    std::size_t number = 0;
    // Each scenario is a "# name (file, seed N)" line, its frames, and "# N frames": a partial
    // with a scenario or a frame taken out is refused, as a results partial is.
    std::uint64_t scenarios = 0, frames = 0;
    const auto count = [&](const std::string& line, std::size_t at) {
      if (!line.starts_with("# ")) {
        ++frames;
        return;
      }
      std::uint64_t said = 0;
      const char* digits = line.data() + 2;
      const char* end = line.data() + line.size();
      const auto [after, ec] = std::from_chars(digits, end, said);
      if (ec == std::errc{} && std::string_view(after, end) == " frames") {
        if (said != frames)
          fail(p.path, "line " + std::to_string(at) + " says " + std::to_string(said) + " frames where its scenario lists " +
                           std::to_string(frames));
      } else {
        ++scenarios;
      }
      frames = 0;
    };
    for (std::string line; std::getline(in, line);) {
      stop_if_interrupted(++number);
      back.push_back(std::move(line));
      if (back.size() <= held) continue;
      count(back.front(), number - held);
      out << back.front() << "\n";
      back.pop_front();
    }
    if (back.size() != held || (held > 1 && !back.front().starts_with("# incomplete: ")))
      fail(p.path, "its last lines are not the \"# incomplete\" lines its mark says");
    if (scenarios + p.mark.not_run.size() != p.mark.items)
      fail(p.path, "holds " + std::to_string(scenarios) + " scenarios and " + std::to_string(p.mark.not_run.size()) +
                       " not run, where its shard has " + std::to_string(p.mark.items));
  }
  const auto v = run_verdict(shards);
  if (!v.incomplete.empty()) TransactionLogWriter::write_incomplete(out, v.incomplete, v.not_run);
}

// A JSON-lines log lists each scenario's frames in a run of records, numbered from 0 without a
// gap (a continuous clock's words are frames of their own), so each record is the next frame of
// the scenario before it or frame 0 of the next scenario (two scenarios may share a name): a
// partial with a frame or a scenario's first frames taken out is refused.
class FrameSequence {
 public:
  explicit FrameSequence(const std::string& path) : path_(path) {}
  void check(const std::string& record, std::size_t line) {
    const json j = json::parse(record);
    const auto scenario = j.find("scenario");
    const auto frame = j.find("frame");
    if (scenario == j.end() || !scenario->is_string() || frame == j.end() || !frame->is_number_unsigned())
      fail(path_, "line " + std::to_string(line) + ": not a frame's record (\"scenario\" and \"frame\")");
    const auto& name = scenario->get_ref<const std::string&>();
    const std::uint64_t index = frame->get<std::uint64_t>();
    const bool next = name == current_ && index == next_;
    if (!next && index != 0)
      fail(path_, "line " + std::to_string(line) + ": frame " + std::to_string(index) + " of \"" + name + "\" follows " +
                      (current_.empty() && next_ == 0 ? std::string("nothing")
                                                      : "frame " + std::to_string(next_ - 1) + " of \"" + current_ + "\"") +
                      ": a frame is missing");
    current_ = name;
    next_ = index + 1;
  }

 private:
  const std::string& path_;
  std::string current_;
  std::uint64_t next_ = 0;
};

void merge_log_json(const std::vector<Partial>& shards, std::ostream& out) {
  for (const auto& p : shards) {
    // Held back: the shard's own "incomplete" record and its mark, which the whole run's end replaces.
    const std::size_t held = 1 + (p.mark.incomplete.empty() ? 0 : 1);
    auto in = open(p.path);
    std::size_t number = 0;
    std::deque<std::string> back;
    FrameSequence frames(p.path);
    for (std::string line; std::getline(in, line);) {
      stop_if_interrupted(number);
      ++number;
      if (!json::accept(line)) fail(p.path, "line " + std::to_string(number) + ": not a JSON record");
      back.push_back(std::move(line));
      if (back.size() <= held) continue;
      frames.check(back.front(), number - held);
      out << back.front() << "\n";
      back.pop_front();
    }
    if (back.size() != held || (held > 1 && !json::parse(back.front()).contains("incomplete")))
      fail(p.path, "its last records are not the \"incomplete\" record its mark says");
  }
  const auto v = run_verdict(shards);
  if (!v.incomplete.empty()) TransactionLogWriter::write_incomplete_json(out, v.incomplete, v.not_run);
}

Sweep merge_sweep(const std::vector<Partial>& shards) {
  Sweep sweep;
  for (const auto& p : shards) {
    json j;
    try {
      j = json::parse(whole_file(p.path));
    } catch (const json::exception& e) {  // syntax, invalid UTF-8, number overflow
      fail(p.path, std::string("not a JSON document: ") + e.what());
    }
    const std::string file = key_of(p.path, j, "", "scenario", &json::is_string, "the scenario file").get<std::string>();
    const std::string name = key_of(p.path, j, "", "name", &json::is_string, "the scenario's name").get<std::string>();
    const auto& points = key_of(p.path, j, "", "points", &json::is_array, "the grid points");
    if (&p == &shards.front()) {
      sweep = {key_of(p.path, p.mark.inputs, "/shard/inputs", "file", &json::is_string, "the scenario file").get<std::string>(),
               name, grid_of(p.path, p.mark.inputs), {}};
      try {
        (void)grid_size(sweep.grid);
      } catch (const ScenarioError& e) {
        fail(p.path, std::string("at /shard/inputs/grid: ") + e.what());
      }
      if (file != sweep.file) fail(p.path, "at /scenario: expected the file its shard swept, " + sweep.file);
    } else if (name != sweep.name || file != sweep.file) {
      fail(p.path, "at /name: the scenario is named \"" + name + "\" where " + shards.front().path + " has \"" + sweep.name + "\"");
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
      const std::string where = "/points/" + std::to_string(i);
      sweep.points.push_back(point_of(p.path, points[i], where));
      if (sweep.points.back().values != grid_point_values(sweep.grid, sweep.points.size() - 1))
        fail(p.path, "at " + where + "/values: not the values of grid point " + std::to_string(sweep.points.size()) +
                         " of the grid its shard names");
    }
  }
  const std::size_t total = grid_size(sweep.grid);
  if (sweep.points.size() != total)
    throw MergeError("the shards hold " + std::to_string(sweep.points.size()) + " points of a grid of " + std::to_string(total));
  return sweep;
}

}  // namespace endatsim::scenarios

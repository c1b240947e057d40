#include "endatsim/scenarios/streamed_outputs.hpp"

#include "endatsim/scenarios/report.hpp"
#include "endatsim/scenarios/transaction_log.hpp"

namespace endatsim::scenarios {
namespace {

using nlohmann::json;

// A value as json_file_text indents it, its lines after the first shifted right by `indent`.
std::string indented(const json& value, std::size_t indent) {
  const std::string text = value.dump(2, ' ', false, json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size() + 64);
  for (const char c : text) {
    out += c;
    if (c == '\n') out.append(indent, ' ');
  }
  return out;
}

// "key": value, at `indent`.
std::string member(const std::string& key, const json& value, std::size_t indent) {
  return std::string(indent, ' ') + json(key).dump(-1, ' ', false, json::error_handler_t::replace) + ": " +
         indented(value, indent);
}

constexpr std::size_t kScenarioIndent = 4, kMemberIndent = 6, kFrameIndent = 8;
constexpr std::array kHeadKeys{"name", "file", "seed"};

void write_head(std::ostream& out, const ScenarioResult& r) {
  out << std::string(kScenarioIndent, ' ') << "{\n";
  out << member("name", r.name, kMemberIndent) << ",\n";
  out << member("file", r.file, kMemberIndent) << ",\n";
  out << member("seed", r.seed, kMemberIndent) << ",\n";
  out << std::string(kMemberIndent, ' ') << "\"frames\": [";
}

void write_frame(std::ostream& out, const ScenarioResult& r, const master::FrameResult& f, bool first) {
  std::string text(first ? "\n" : ",\n");
  text.append(kFrameIndent, ' ');
  frame_tokens(r, f).sorted_indented(text, kFrameIndent);
  out << text;
}

void write_tail(std::ostream& out, const ScenarioResult& r, std::size_t frames) {
  out << (frames == 0 ? "]" : "\n" + std::string(kMemberIndent, ' ') + "]");
  json rest = result_json_without_frames(r);
  for (const char* key : kHeadKeys) rest.erase(key);
  for (const auto& [key, value] : rest.items()) out << ",\n" << member(key, value, kMemberIndent);
  out << "\n" << std::string(kScenarioIndent, ' ') << "}";
}

}  // namespace

void TransactionLogWriter::begin(const ScenarioResult& h) {
  if (format_ != Format::Text) return;
  out_ << "# " << h.name << " (" << h.file << ", seed " << h.seed << ")\n";
  for (const auto& c : h.conformance)
    if (!c.relaxed_by.empty()) out_ << "# relaxed by option: " << c.check << " (" << c.relaxed_by << ")\n";
}

void TransactionLogWriter::frame(const ScenarioResult& h, const master::FrameResult& f,
                                 std::span<const checker::Violation> findings) {
  if (format_ == Format::Text) {
    out_ << transaction_line(transaction_tokens(f, findings)) << "\n";
    return;
  }
  line_.clear();
  transaction_tokens(f, findings, &h.name).compact(line_);
  line_ += '\n';
  out_ << line_;
}

void TransactionLogWriter::end(const ScenarioResult& r) {
  if (format_ != Format::Text) return;
  out_ << "# " << r.tally.results << " frames\n";
}

void TransactionLogWriter::write_incomplete(std::ostream& out, const std::string& incomplete,
                                            const std::vector<NotRun>& not_run) {
  out << "# incomplete: " << incomplete << "\n";
  for (const auto& n : not_run) out << "# " << n.file << ": " << n.reason << "\n";
}

void TransactionLogWriter::write_incomplete_json(std::ostream& out, const std::string& incomplete,
                                                 const std::vector<NotRun>& not_run) {
  json files = json::array();
  for (const auto& n : not_run) files.push_back({{"file", n.file}, {"reason", n.reason}});
  out << json{{"incomplete", incomplete}, {"not_run", files}}.dump(-1, ' ', false, json::error_handler_t::replace) << "\n";
}

ResultsJsonWriter::ResultsJsonWriter(std::ostream& out, const std::string& version) : out_(out) {
  out_ << "{\n" << member("endatsim", version, 2) << ",\n  \"scenarios\": [";
}

void ResultsJsonWriter::begin(const ScenarioResult& h) {
  out_ << (scenarios_ == 0 ? "\n" : ",\n");
  write_head(out_, h);
  frames_ = 0;
}

void ResultsJsonWriter::frame(const ScenarioResult& h, const master::FrameResult& f, std::span<const checker::Violation>) {
  write_frame(out_, h, f, frames_++ == 0);
}

void ResultsJsonWriter::end(const ScenarioResult& r) {
  write_tail(out_, r, frames_);
  ++scenarios_;
}

void ResultsJsonWriter::copy_scenario(const std::function<void(std::ostream&)>& object) {
  out_ << (scenarios_ == 0 ? "\n" : ",\n");
  object(out_);
  ++scenarios_;
}

void ResultsJsonWriter::finish(bool passed, const std::string& incomplete, const std::vector<std::string>& not_run,
                               const json* shard) {
  out_ << (scenarios_ == 0 ? "]" : "\n  ]");
  json rest{{"passed", passed}};
  if (!incomplete.empty()) {
    rest["complete"] = false;
    rest["incomplete"] = incomplete;
    if (!not_run.empty()) rest["not_run"] = not_run;
  }
  if (shard != nullptr) rest["shard"] = *shard;
  for (const auto& [key, value] : rest.items()) out_ << ",\n" << member(key, value, 2);
  out_ << "\n}\n";
}

void write_result_json(std::ostream& out, const ScenarioResult& r) {
  write_head(out, r);
  for (std::size_t i = 0; i < r.frames.size(); ++i) write_frame(out, r, r.frames[i], i == 0);
  write_tail(out, r, r.frames.size());
}

}  // namespace endatsim::scenarios

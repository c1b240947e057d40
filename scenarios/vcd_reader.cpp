#include "endatsim/scenarios/vcd_reader.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace endatsim::scenarios {
namespace {

constexpr std::size_t kMaxIssues = 100;

struct Token {
  std::string text;
  std::size_t line;
};

class Tokens {
 public:
  explicit Tokens(const std::string& text) : text_(text) {}
  bool next(Token& t) {
    while (pos_ < text_.size() && is_space(text_[pos_])) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
    if (pos_ >= text_.size()) return false;
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
    t = Token{text_.substr(start, pos_ - start), line_};
    return true;
  }
  std::size_t line() const { return line_; }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }
  const std::string& text_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
};

bool all_digits(const std::string& s) {
  return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
}

std::int64_t unit_ps(const std::string& unit) {
  if (unit == "s") return 1'000'000'000'000;
  if (unit == "ms") return 1'000'000'000;
  if (unit == "us") return 1'000'000;
  if (unit == "ns") return 1'000;
  if (unit == "ps") return 1;
  return 0;  // fs and anything else: not a whole number of picoseconds
}

bool valid_id(const std::string& id) {
  if (id.empty()) return false;
  for (char c : id)
    if (c < '!' || c > '~') return false;
  return true;
}

class Parser {
 public:
  Parser(const std::string& text, const VcdLintOptions& o) : tokens_(text), options_(o) {}

  VcdFile run() {
    Token t;
    while (tokens_.next(t)) {
      if (t.text[0] == '$') keyword(t);
      else if (t.text[0] == '#') timestamp(t);
      else value_change(t);
    }
    if (!body_) issue(tokens_.line(), "no $enddefinitions: the file has no value section");
    if (file_.timescale.empty()) issue(1, "no $timescale: viewers assume 1 s per unit");
    file_.end_time = last_time_ < 0 ? 0 : last_time_;
    for (auto& v : file_.variables)
      for (std::size_t i = 1; i < v.changes.size(); ++i) {
        if (v.changes[i - 1].value == '0' && v.changes[i].value == '1') ++v.rising;
        if (v.changes[i - 1].value == '1' && v.changes[i].value == '0') ++v.falling;
      }
    return std::move(file_);
  }

 private:
  void issue(std::size_t line, std::string message) {
    if (file_.issues.size() < kMaxIssues) file_.issues.push_back({line, std::move(message)});
  }

  // Tokens up to the closing $end; false (and an issue) when the file ends first.
  bool until_end(const Token& opener, std::vector<Token>& out) {
    Token t;
    while (tokens_.next(t)) {
      if (t.text == "$end") return true;
      out.push_back(t);
    }
    issue(opener.line, opener.text + " without $end");
    return false;
  }

  void keyword(const Token& t) {
    std::vector<Token> args;
    const std::string& k = t.text;
    if (k == "$comment" || k == "$date" || k == "$version") {
      until_end(t, args);
      if (body_ && k == "$comment" && options_.sigrok)
        issue(t.line, "$comment after $enddefinitions: sigrok-cli reads nothing from such a file");
    } else if (k == "$timescale") {
      if (!until_end(t, args)) return;
      timescale(t, args);
    } else if (k == "$scope") {
      if (!until_end(t, args)) return;
      if (body_) issue(t.line, "$scope after $enddefinitions");
      if (args.size() != 2) issue(t.line, "$scope expects a type and a name");
      else scopes_.push_back(args[1].text);
    } else if (k == "$upscope") {
      if (!until_end(t, args)) return;
      if (body_) issue(t.line, "$upscope after $enddefinitions");
      if (scopes_.empty()) issue(t.line, "$upscope without an open $scope");
      else scopes_.pop_back();
    } else if (k == "$var") {
      if (!until_end(t, args)) return;
      variable(t, args);
    } else if (k == "$enddefinitions") {
      until_end(t, args);
      if (body_) issue(t.line, "second $enddefinitions");
      if (!scopes_.empty()) issue(t.line, "$enddefinitions inside an open $scope " + scopes_.back());
      body_ = true;
    } else if (k == "$dumpvars" || k == "$dumpall" || k == "$dumpon" || k == "$dumpoff") {
      if (!body_) issue(t.line, k + " before $enddefinitions");
      if (last_time_ < 0) issue(t.line, k + " before the first timestamp");
      in_dump_ = true;
    } else if (k == "$end" && in_dump_) {
      in_dump_ = false;
    } else {
      issue(t.line, "unknown keyword " + k);
    }
  }

  void timescale(const Token& t, const std::vector<Token>& args) {
    std::string joined;
    for (const auto& a : args) joined += a.text;
    const auto digits = joined.find_first_not_of("0123456789");
    const std::string number = joined.substr(0, digits), unit = digits == std::string::npos ? "" : joined.substr(digits);
    if (number != "1" && number != "10" && number != "100") {
      issue(t.line, "$timescale expects 1, 10 or 100 and a unit, got '" + joined + "'");
      return;
    }
    if (unit != "s" && unit != "ms" && unit != "us" && unit != "ns" && unit != "ps" && unit != "fs") {
      issue(t.line, "$timescale unit must be s, ms, us, ns, ps or fs, got '" + unit + "'");
      return;
    }
    file_.timescale = joined;
    file_.timescale_ps = std::stoll(number) * unit_ps(unit);
  }

  void variable(const Token& t, const std::vector<Token>& args) {
    if (body_) issue(t.line, "$var after $enddefinitions");
    if (args.size() != 4 && args.size() != 5) {
      issue(t.line, "$var expects: type width identifier name [index] $end");
      return;
    }
    if (!all_digits(args[1].text) || args[1].text.size() > 6 || std::stoul(args[1].text) == 0) {
      issue(t.line, "$var width must be a positive integer, got '" + args[1].text + "'");
      return;
    }
    if (!valid_id(args[2].text)) {
      issue(t.line, "$var identifier must be printable ASCII, got '" + args[2].text + "'");
      return;
    }
    VcdVariable v;
    v.type = args[0].text;
    v.width = static_cast<unsigned>(std::stoul(args[1].text));
    v.id = args[2].text;
    for (const auto& s : scopes_) v.name += s + ".";
    v.name += args[3].text;
    if (options_.sigrok && v.type == "string")
      issue(t.line, "text variable " + v.name + ": sigrok-cli skips its values, with a warning for each");
    else if (options_.sigrok && v.width != 1)
      issue(t.line, "vector variable " + v.name + " (width " + args[1].text + "): sigrok-cli drops it silently");
    if (ids_.count(v.id) != 0) {
      // An alias of an earlier variable: legal VCD, one value for both.
      return;
    }
    if (file_.find(v.name) != nullptr) issue(t.line, "variable " + v.name + " declared twice");
    ids_[v.id] = file_.variables.size();
    file_.variables.push_back(std::move(v));
  }

  void timestamp(const Token& t) {
    const std::string digits = t.text.substr(1);
    if (!body_) issue(t.line, "timestamp before $enddefinitions");
    if (!all_digits(digits) || digits.size() > 18) {
      issue(t.line, "timestamp must be # and a non-negative integer, got '" + t.text + "'");
      return;
    }
    const std::int64_t time = std::stoll(digits);
    if (time <= last_time_)
      issue(t.line, "time does not increase: #" + digits + " after #" + std::to_string(last_time_));
    last_time_ = std::max(last_time_, time);
  }

  VcdVariable* target(const Token& t, const std::string& id) {
    if (!body_) issue(t.line, "value change before $enddefinitions");
    else if (last_time_ < 0) issue(t.line, "value change before the first timestamp");
    const auto it = ids_.find(id);
    if (it == ids_.end()) {
      issue(t.line, "value change for undeclared identifier '" + id + "'");
      return nullptr;
    }
    return &file_.variables[it->second];
  }

  // Several values at one timestamp: the last one counts, as in every viewer.
  void record(VcdVariable& v, char value) {
    value = static_cast<char>(value == 'X' ? 'x' : value == 'Z' ? 'z' : value);
    const std::int64_t now = std::max<std::int64_t>(last_time_, 0);
    if (!v.changes.empty() && v.changes.back().time == now) v.changes.pop_back();
    if (!v.changes.empty() && v.changes.back().value == value) return;
    v.changes.push_back({now, value});
  }

  void value_change(const Token& t) {
    const char c = t.text[0];
    if (c == '0' || c == '1' || c == 'x' || c == 'X' || c == 'z' || c == 'Z') {
      VcdVariable* v = target(t, t.text.substr(1));
      if (v == nullptr) return;
      if (v->width != 1) issue(t.line, "scalar value for " + v->name + " of width " + std::to_string(v->width));
      record(*v, c);
      return;
    }
    if (c == 's' || c == 'S') {  // GTKWave's text value: any token, then the identifier
      Token id;
      if (!tokens_.next(id)) {
        issue(t.line, "text value " + t.text + " without an identifier");
        return;
      }
      VcdVariable* v = target(id, id.text);
      if (v != nullptr && v->type != "string") issue(t.line, "text value for " + v->name + ", which is no string variable");
      return;
    }
    if (c == 'b' || c == 'B' || c == 'r' || c == 'R') {
      Token id;
      if (!tokens_.next(id)) {
        issue(t.line, "vector value " + t.text + " without an identifier");
        return;
      }
      const std::string bits = t.text.substr(1);
      const bool binary = c == 'b' || c == 'B';
      if (binary && (bits.empty() || bits.find_first_not_of("01xXzZ") != std::string::npos))
        issue(t.line, "vector value must be b followed by 0, 1, x or z, got '" + t.text + "'");
      if (!binary) {
        std::istringstream in(bits);
        double d = 0;
        if (bits.empty() || !(in >> d) || !in.eof()) issue(t.line, "real value must be r and a number, got '" + t.text + "'");
      }
      VcdVariable* v = target(id, id.text);
      if (v == nullptr) return;
      if (binary && bits.size() > v->width)
        issue(t.line, "vector value of " + std::to_string(bits.size()) + " bits for " + v->name + " of width " +
                          std::to_string(v->width));
      if (binary && !bits.empty()) record(*v, bits.back());
      return;
    }
    issue(t.line, "not a value change, timestamp or keyword: '" + t.text + "'");
  }

  Tokens tokens_;
  VcdLintOptions options_;
  VcdFile file_;
  std::vector<std::string> scopes_;
  std::map<std::string, std::size_t> ids_;
  bool body_ = false;
  bool in_dump_ = false;
  std::int64_t last_time_ = -1;
};

}  // namespace

const VcdVariable* VcdFile::find(const std::string& name) const {
  for (const auto& v : variables)
    if (v.name == name) return &v;
  return nullptr;
}

VcdFile parse_vcd(const std::string& text, const VcdLintOptions& options) { return Parser(text, options).run(); }

VcdFile read_vcd_file(const std::string& path, const VcdLintOptions& options) {
  // Looked at before it is opened: a FIFO would wait for a writer, a device never end.
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw std::runtime_error("'" + path + "' is not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open '" + path + "': " + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_vcd(ss.str(), options);
}

}  // namespace endatsim::scenarios

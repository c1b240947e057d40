#include "endatsim/input/json_input.hpp"

#include "endatsim/input/suggest.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace endatsim::input {
namespace {

std::string describe(const json& j) {
  if (j.is_null()) return "null";
  std::string dump = j.dump(-1, ' ', true, json::error_handler_t::replace);
  if (dump.size() > 40) dump = dump.substr(0, 37) + "...";
  return std::string(j.type_name()) + " " + dump;
}

std::string at(const std::string& file, const std::string& path) {
  return file + ": at " + trimmed(path.empty() ? "/" : path, 200) + ": ";
}

// Follows where the parser is, to refuse what nlohmann::json accepts silently: nesting deeper
// than kMaxDepth and a key given twice in one object (the last would win).
class ParseGuard {
 public:
  // `where` follows the path of the value read next, for errors nlohmann reports without one.
  ParseGuard(const std::string& file, std::string& where) : file_(file), where_(&where) {}

  bool operator()(int depth, json::parse_event_t event, json& parsed) {
    using E = json::parse_event_t;
    if (static_cast<std::size_t>(depth) > kMaxDepth)
      throw InputError(at(file_, next_path()) + "nested deeper than " + std::to_string(kMaxDepth) + " levels");
    switch (event) {
      case E::object_start:
      case E::array_start:
        next_element();
        stack_.push_back({event == E::array_start, -1, {}, {}});
        break;
      case E::object_end:
      case E::array_end:
        stack_.pop_back();
        break;
      case E::key: {
        Level& top = stack_.back();
        top.key = parsed.get<std::string>();
        if (!top.keys.insert(top.key).second)
          throw InputError(at(file_, path()) + "duplicate key \"" + trimmed(top.key) +
                           "\" (each key may appear once per object)");
        break;
      }
      case E::value:
        next_element();
        break;
    }
    *where_ = next_path();
    return true;
  }

 private:
  struct Level {
    bool array;
    long index;
    std::string key;
    std::set<std::string> keys;
  };
  void next_element() {
    if (!stack_.empty() && stack_.back().array) ++stack_.back().index;
  }
  std::string path() const {
    std::string p;
    for (const Level& l : stack_) p += "/" + (l.array ? std::to_string(l.index) : l.key);
    return p;
  }
  // Like path(), but an array's last index is that of the element that comes next.
  std::string next_path() const {
    std::string p;
    for (std::size_t i = 0; i < stack_.size(); ++i) {
      const Level& l = stack_[i];
      p += "/" + (l.array ? std::to_string(i + 1 == stack_.size() ? l.index + 1 : l.index) : l.key);
    }
    return p.empty() ? "/" : p;
  }
  const std::string& file_;
  std::string* where_;
  std::vector<Level> stack_;
};

}  // namespace

std::string trimmed(const std::string& text, std::size_t max) {
  if (text.size() <= max) return text;
  std::size_t cut = max;
  // Not inside a UTF-8 sequence.
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;
  return text.substr(0, cut) + "... (" + std::to_string(text.size()) + " bytes)";
}

std::string read_file(const std::string& path, FileKind kind) {
  const std::string noun(kind.noun);
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw InputError(path + ": not a regular file, expected a JSON " + noun);
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int error = errno;
    throw InputError(path + ": cannot open the file" + (error != 0 ? std::string(": ") + std::strerror(error) : std::string()));
  }
  std::string text;
  char buffer[65536];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxFileBytes)
      throw InputError(path + ": larger than 4 MiB, not " + std::string(kind.article) + " " + noun);
  }
  if (in.bad()) throw InputError(path + ": cannot read the file: " + std::strerror(errno));
  if (text.empty()) throw InputError(path + ": at /: empty file, expected a JSON " + noun + " object");
  return text;
}

json parse(const std::string& text, const std::string& file) {
  json root;
  std::string where = "/";
  try {
    root = json::parse(text, ParseGuard(file, where));
  } catch (const json::exception& e) {  // syntax, invalid UTF-8, number overflow
    const std::string what = e.what();
    const auto bracket = what.find("] ");
    const std::string place = e.id == 406 ? "at " + trimmed(where, 200) + ": " : "";  // 406: number overflow, reported without a place
    throw InputError(file + ": " + place + "not valid JSON: " +
                     trimmed(bracket == std::string::npos ? what : what.substr(bracket + 2), 2000));
  }
  // The parser takes a NUL byte for the end of the input: what it read may have parsed while the
  // bytes after it were never looked at.
  if (const auto nul = text.find('\0'); nul != std::string::npos) {
    const auto before = text.begin() + static_cast<std::ptrdiff_t>(nul);
    const std::size_t line = 1 + static_cast<std::size_t>(std::count(text.begin(), before, '\n'));
    const std::size_t line_start = text.rfind('\n', nul == 0 ? 0 : nul - 1);
    const std::size_t column = line_start == std::string::npos || nul == 0 ? nul + 1 : nul - line_start;
    throw InputError(file + ": not valid JSON: a NUL byte at line " + std::to_string(line) + ", column " +
                     std::to_string(column) + " (a JSON file is text; expected a JSON value or the end of the file)");
  }
  return root;
}

void Node::fail(const std::string& expected) const { fail_raw("expected " + expected + ", got " + describe(j_)); }

void Node::fail_choice(const std::vector<std::string>& names) const {
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "\"" : ", \"") + n + "\"";
  const std::string hint = j_.is_string() ? did_you_mean(j_.get_ref<const std::string&>(), names) : std::string();
  fail_raw("expected one of " + list + ", got " + describe(j_) + (hint.empty() ? "" : " (" + hint.substr(0, hint.size() - 1) + ")"));
}

// A path or message from a hostile file (a key of megabytes) is cut, not echoed whole.
void Node::fail_raw(const std::string& message) const { throw InputError(at(file_, path_) + trimmed(message, 2000)); }

Node Node::child(const std::string& key) const { return Node(j_.at(key), path_ + "/" + key, file_); }

Node Node::item(std::size_t i) const { return Node(j_.at(i), path_ + "/" + std::to_string(i), file_); }

std::string Node::as_string() const {
  if (!j_.is_string()) fail("a string");
  return j_.get<std::string>();
}

bool Node::as_bool() const {
  if (!j_.is_boolean()) fail("true or false");
  return j_.get<bool>();
}

std::uint64_t Node::as_uint(std::uint64_t min, std::uint64_t max) const {
  const std::string range = "an integer " + std::to_string(min) + " .. " + std::to_string(max);
  if (!j_.is_number_integer() && !j_.is_number_unsigned()) fail(range);
  if (j_.is_number_integer() && !j_.is_number_unsigned() && j_.get<std::int64_t>() < 0) fail(range);
  const auto v = j_.get<std::uint64_t>();
  if (v < min || v > max) fail(range);
  return v;
}

std::int64_t Node::as_int(std::int64_t min, std::int64_t max) const {
  const std::string range = "an integer " + std::to_string(min) + " .. " + std::to_string(max);
  if (j_.is_number_unsigned() && j_.get<std::uint64_t>() > static_cast<std::uint64_t>(max)) fail(range);
  if (!j_.is_number_integer()) fail(range);
  const auto v = j_.get<std::int64_t>();
  if (v < min || v > max) fail(range);
  return v;
}

double Node::as_number(double min, double max, const std::string& unit) const {
  std::ostringstream range;
  range << "a number " << min << " .. " << max << unit;
  if (!j_.is_number()) fail(range.str());
  const double v = j_.get<double>();
  if (!std::isfinite(v) || v < min || v > max) fail(range.str());
  return v;
}

sim::Time Node::as_duration(sim::Time min, sim::Time max) const {
  const std::string range =
      "a duration string " + sim::format_time(min) + " .. " + sim::format_time(max) + " such as \"2.5 us\"";
  if (!j_.is_string()) fail(range);
  sim::Time t;
  try {
    t = sim::parse_duration(j_.get<std::string>());
  } catch (const sim::ValueTooLarge&) {
    fail(range);  // beyond any range: say which one applies here
  } catch (const std::invalid_argument& e) {
    fail_raw(e.what());
  }
  if (t < min || t > max) fail(range);
  return t;
}

sim::Hertz Node::as_frequency(sim::Hertz min, sim::Hertz max, bool or_zero) const {
  const std::string range = "a frequency string " + std::string(or_zero ? "0 Hz or " : "") + sim::format_frequency(min) +
                            " .. " + sim::format_frequency(max) + " such as \"2 MHz\"";
  if (!j_.is_string()) fail(range);
  sim::Hertz f = 0;
  try {
    f = sim::parse_frequency(j_.get<std::string>());
  } catch (const sim::ValueTooLarge&) {
    fail(range);
  } catch (const std::invalid_argument& e) {
    fail_raw(e.what());
  }
  if ((f < min && !(or_zero && f == 0)) || f > max) fail(range);
  return f;
}

std::uint64_t Node::as_word(std::uint64_t max) const {
  const std::string what = "an integer 0 .. " + std::to_string(max) + " or a hex string such as \"0x1F\"";
  if (!j_.is_string()) {
    if (!j_.is_number_unsigned() && !(j_.is_number_integer() && j_.get<std::int64_t>() >= 0)) fail(what);
    if (j_.get<std::uint64_t>() > max) fail(what);
    return j_.get<std::uint64_t>();
  }
  const std::string s = j_.get<std::string>();
  const bool hex = s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X');
  const std::string digits = hex ? s.substr(2) : s;
  if (digits.empty() || digits.size() > kWordStringDigits ||
      digits.find_first_not_of(hex ? "0123456789abcdefABCDEF" : "0123456789") != std::string::npos)
    fail(what);
  const std::uint64_t v = std::stoull(digits, nullptr, hex ? 16 : 10);
  if (v > max) fail(what);
  return v;
}

namespace {

// One digit in a regular expression: a hex letter in either case.
std::string digit_pattern(unsigned d) {
  if (d < 10) return std::string(1, static_cast<char>('0' + d));
  return std::string("[") + static_cast<char>('a' + d - 10) + static_cast<char>('A' + d - 10) + "]";
}

// The digits first .. last inside a character class: "0-4", "5-9a-cA-C".
std::string class_runs(unsigned first, unsigned last) {
  const auto one = [](unsigned d, bool upper) {
    return static_cast<char>(d < 10 ? '0' + d : (upper ? 'A' : 'a') + d - 10);
  };
  const auto run = [&](unsigned a, unsigned b, bool upper) {
    std::string r(1, one(a, upper));
    if (b > a) r += std::string(b > a + 1 ? "-" : "") + one(b, upper);
    return r;
  };
  std::string out;
  if (first < 10) out += run(first, std::min(last, 9U), true);
  if (last >= 10) {
    const unsigned a = std::max(first, 10U);
    out += run(a, last, false) + run(a, last, true);
  }
  return out;
}

// Any digit of `base`, `count` times.
std::string any_digits(unsigned base, std::size_t count) {
  if (count == 0) return "";
  const std::string any = base == 16 ? "[0-9a-fA-F]" : "[0-9]";
  return count == 1 ? any : any + "{" + std::to_string(count) + "}";
}

// The numbers lo .. hi of one length (digits most significant first), the classic way: a common
// first digit, else the part below the first whole block, the whole blocks, the part above.
std::string range_pattern(const std::vector<unsigned>& lo, const std::vector<unsigned>& hi, unsigned base) {
  if (lo.size() == 1) return lo[0] == hi[0] ? digit_pattern(lo[0]) : "[" + class_runs(lo[0], hi[0]) + "]";
  const std::vector<unsigned> lo_rest(lo.begin() + 1, lo.end()), hi_rest(hi.begin() + 1, hi.end());
  if (lo[0] == hi[0]) return digit_pattern(lo[0]) + "(?:" + range_pattern(lo_rest, hi_rest, base) + ")";
  const bool lo_whole = std::all_of(lo_rest.begin(), lo_rest.end(), [](unsigned d) { return d == 0; });
  const bool hi_whole = std::all_of(hi_rest.begin(), hi_rest.end(), [base](unsigned d) { return d == base - 1; });
  std::vector<std::string> parts;
  if (!lo_whole) parts.push_back(digit_pattern(lo[0]) + "(?:" + range_pattern(lo_rest, std::vector<unsigned>(lo_rest.size(), base - 1), base) + ")");
  const unsigned first = lo_whole ? lo[0] : lo[0] + 1, last = hi_whole ? hi[0] : hi[0] - 1;
  if (first <= last)
    parts.push_back((first == last ? digit_pattern(first) : "[" + class_runs(first, last) + "]") + any_digits(base, lo_rest.size()));
  if (!hi_whole) parts.push_back(digit_pattern(hi[0]) + "(?:" + range_pattern(std::vector<unsigned>(hi_rest.size(), 0), hi_rest, base) + ")");
  std::string out;
  for (const auto& part : parts) out += (out.empty() ? "" : "|") + part;
  return out;
}

std::vector<unsigned> digits_of(std::uint64_t v, unsigned base) {
  std::vector<unsigned> digits;
  for (std::uint64_t x = v; digits.empty() || x != 0; x /= base) digits.insert(digits.begin(), static_cast<unsigned>(x % base));
  return digits;
}

// The values min .. max written in `base`, each with as many leading zeros as the digit limit leaves.
std::string values_pattern(std::uint64_t min, std::uint64_t max, unsigned base) {
  std::string out;
  for (std::uint64_t from = min;;) {
    const std::vector<unsigned> lo = digits_of(from, base);
    std::uint64_t top = 1;  // base^length - 1: the largest value of this length
    for (std::size_t i = 0; i < lo.size(); ++i) top *= base;
    const std::uint64_t to = std::min(max, top - 1);
    out += (out.empty() ? "" : "|") + ("0{0," + std::to_string(kWordStringDigits - lo.size()) + "}(?:" +
                                       range_pattern(lo, digits_of(to, base), base) + ")");
    if (to == max) return out;
    from = to + 1;
  }
}

}  // namespace

std::string word_string_pattern(std::uint64_t min, std::uint64_t max) {
  if (min > max || digits_of(max, 10).size() > kWordStringDigits)
    throw std::invalid_argument("word_string_pattern: " + std::to_string(min) + " .. " + std::to_string(max) +
                                " is empty or beyond " + std::to_string(kWordStringDigits) + " digits");
  return "^(?:0[xX](?:" + values_pattern(min, max, 16) + ")|(?:" + values_pattern(min, max, 10) + "))$";
}

std::uint16_t Node::as_hex_word() const {
  const std::string what = "a 16-bit word as a hex string such as \"0x8019\"";
  if (!j_.is_string()) fail(what);
  const std::string& s = j_.get_ref<const std::string&>();
  if (s.size() < 3 || s.size() > 6 || s[0] != '0' || (s[1] != 'x' && s[1] != 'X') ||
      s.find_first_not_of("0123456789abcdefABCDEF", 2) != std::string::npos)
    fail(what);
  return static_cast<std::uint16_t>(std::stoul(s.substr(2), nullptr, 16));
}

Object::Object(const Node& n) : n_(n) {
  if (!n.raw().is_object()) n.fail("an object");
}

std::optional<Node> Object::opt(const std::string& key) {
  known_.insert(key);
  const auto it = n_.raw().find(key);
  if (it == n_.raw().end()) return std::nullopt;
  return Node(*it, n_.path() + "/" + key, n_.file());
}

Node Object::req(const std::string& key) {
  auto n = opt(key);
  if (n) return *n;
  // A key of this object close to the one required is most likely it, misspelt: say which.
  const std::vector<std::string> wanted{key};
  for (const auto& [given, value] : n_.raw().items())
    if (known_.count(given) == 0 && closest_match(given, wanted))
      n_.fail_raw("missing required key \"" + key + "\" (did you mean it for \"" + trimmed(given) + "\"?)");
  n_.fail_raw("missing required key \"" + key + "\"");
}

void Object::done() const {
  for (const auto& [key, value] : n_.raw().items()) {
    if (known_.count(key) != 0) continue;
    const std::vector<std::string> known(known_.begin(), known_.end());
    std::string names;
    for (const auto& k : known) names += (names.empty() ? "" : ", ") + k;
    n_.fail_raw("unknown key \"" + trimmed(key) + "\" (" + did_you_mean(key, known) + "expected one of: " + names + ")");
  }
}

}  // namespace endatsim::input

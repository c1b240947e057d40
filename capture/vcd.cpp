// VCD (IEEE 1364 section 18) as HDL simulators write it: Icarus, GHDL, Verilator and commercial
// ones. Any $timescale (1, 10 or 100 of s .. fs; femtoseconds are rounded to the picosecond,
// which is then the resolution),
// nested scopes, identifiers of any printable characters, vectors split into one signal per bit
// ("data[3]"), std_logic values (U X Z W - unknown, H and L weak 1 and 0), real and text (GTKWave's "string") variables ignored.
// The body is streamed token by token.
#include <cerrno>
#include <cstring>
#include <algorithm>
#include <array>
#include <charconv>
#include <climits>
#include <fstream>
#include <map>
#include <optional>
#include <string_view>
#include <sys/stat.h>
#include <unordered_map>

#include "endatsim/capture/queued_reader.hpp"

namespace endatsim::capture {
namespace {

class TokenStream {
 public:
  explicit TokenStream(const std::string& path) : in_(path, std::ios::binary) {}
  bool good() const { return static_cast<bool>(in_); }
  // The next whitespace-separated token; false at the end of the file. The token is a view into
  // the buffer, valid until the next call; only one that runs across the buffer's end is copied
  // (a capture is millions of short tokens).
  bool next(std::string_view& token) {
    for (;;) {  // the whitespace before it
      if (pos_ == end_ && !fill()) {
        token_line_ = line_;
        token = {};
        return false;
      }
      const char c = buffer_[pos_];
      if (!is_space(c)) break;
      if (c == '\n') ++line_;
      ++pos_;
      ++consumed_;
    }
    token_line_ = line_;
    const std::size_t from = pos_;
    pos_ = scan(pos_, std::min(end_, pos_ + kMaxToken + 1));
    consumed_ += pos_ - from;
    if (pos_ < end_ || pos_ - from > kMaxToken) {
      token = std::string_view(buffer_.data() + from, pos_ - from);
      if (token.size() <= kMaxToken) take_separator();
      return true;
    }
    spill_.assign(buffer_.data() + from, pos_ - from);
    for (;;) {  // the token runs on after the buffer's end
      if (!fill()) {
        unterminated_ = true;
        token = spill_;
        return true;
      }
      const std::size_t rest = pos_;
      pos_ = scan(pos_, std::min(end_, pos_ + kMaxToken + 1 - spill_.size()));
      spill_.append(buffer_.data() + rest, pos_ - rest);
      consumed_ += pos_ - rest;
      token = spill_;
      if (spill_.size() > kMaxToken) return true;  // the caller rejects it
      if (pos_ < end_) {
        take_separator();
        return true;
      }
    }
  }
  bool next(std::string& token) {
    std::string_view view;
    const bool found = next(view);
    token.assign(view);
    return found;
  }
  // The last token ran into the end of the file: a writer ends every line, so the file was cut.
  bool unterminated() const { return unterminated_; }
  // The line the last token began on (at the end of the file: the last line).
  std::size_t line() const { return token_line_; }
  std::uint64_t consumed() const { return consumed_; }
  static constexpr std::size_t kMaxToken = 4096;

 private:
  // A NUL is no part of any VCD token: it separates them like a space. A table: this is asked of
  // every character of a capture.
  static constexpr std::array<bool, 256> kSpace = [] {
    std::array<bool, 256> space{};
    for (const char c : {' ', '\t', '\n', '\r', '\f', '\v', '\0'}) space[static_cast<unsigned char>(c)] = true;
    return space;
  }();
  static bool is_space(char c) { return kSpace[static_cast<unsigned char>(c)]; }
  // The first whitespace in [from, stop), or stop. In locals: stores to a member would have to be
  // kept in step with the character loads, which may alias them.
  std::size_t scan(std::size_t from, std::size_t stop) const {
    const char* const text = buffer_.data();
    std::size_t at = from;
    while (at < stop && !is_space(text[at])) ++at;
    return at;
  }
  // The whitespace that ends a token is taken with it.
  void take_separator() {
    if (buffer_[pos_] == '\n') ++line_;
    ++pos_;
    ++consumed_;
    unterminated_ = false;
  }
  bool fill() {
    in_.read(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    end_ = static_cast<std::size_t>(in_.gcount());
    pos_ = 0;
    return end_ != 0;
  }
  std::ifstream in_;
  std::array<char, 1 << 16> buffer_{};
  std::string spill_;  // a token across the buffer's end
  std::size_t pos_ = 0;
  std::size_t end_ = 0;
  std::size_t line_ = 1;
  std::size_t token_line_ = 1;
  bool unterminated_ = false;
  std::uint64_t consumed_ = 0;
};

char normalize(char v) {
  switch (v) {
    case '0': case 'L': case 'l': return '0';
    case '1': case 'H': case 'h': return '1';
    case 'x': case 'X': case 'z': case 'Z': case 'U': case 'u': case 'W': case 'w': case '-': return 'x';
    default: return '?';
  }
}

class VcdReader final : public QueuedReader {
 public:
  explicit VcdReader(const std::string& path) : QueuedReader(path), tokens_(path) {
    if (!tokens_.good()) throw CaptureError(path + ": cannot open the capture for reading: " + std::strerror(errno));
    header();
    reset_levels();
  }

  std::uint64_t bytes_read() const override { return tokens_.consumed(); }
  Time end() const override { return now_; }
  // Times finer than the picosecond are rounded to the nearest one: an edge may be off by half
  // a picosecond, a duration between two by up to one. A file in such a timescale whose times all
  // fall on whole picoseconds (GHDL writes every VCD in 1 fs) is exact until one does not.
  Time uncertainty() const override { return rounded_ ? Time{1} : Time::zero(); }
  std::string timescale() const override { return timescale_; }

 private:
  bool refill() override { return body_token(); }

  struct Variable {
    std::uint32_t first = 0;  // index of its most significant bit's signal
    unsigned width = 1;
    bool real = false;
  };

  [[noreturn]] void fail(const std::string& what) const {
    throw CaptureError(path_ + ": line " + std::to_string(tokens_.line()) + ": " + what);
  }

  std::string token(const char* expecting) {
    std::string t;
    if (!tokens_.next(t)) fail(std::string("the file ends where ") + expecting + " was expected (truncated?)");
    if (t.size() > TokenStream::kMaxToken) fail("a token longer than " + std::to_string(TokenStream::kMaxToken) + " characters");
    return t;
  }

  void skip_to_end(const std::string& keyword) {
    for (std::string t = token(("$end of " + keyword).c_str()); t != "$end"; t = token(("$end of " + keyword).c_str())) {
    }
  }

  void header() {
    std::string first;
    if (!tokens_.next(first)) fail("empty file: no VCD header");
    if (first.empty() || first[0] != '$') fail("not a VCD file: it does not begin with a $ keyword (got '" + first.substr(0, 40) + "')");
    std::string t = first;
    while (true) {
      if (t == "$enddefinitions") {
        skip_to_end(t);
        break;
      }
      if (t == "$timescale") timescale();
      else if (t == "$scope") {
        token("the scope's type");
        scopes_.push_back(token("the scope's name"));
        skip_to_end(t);
      } else if (t == "$upscope") {
        if (scopes_.empty()) fail("$upscope without a $scope");
        scopes_.pop_back();
        skip_to_end(t);
      } else if (t == "$var") variable();
      else if (t[0] == '$') skip_to_end(t);
      else fail("'" + t.substr(0, 40) + "' in the header, where a $ keyword was expected");
      t = token("$enddefinitions");
    }
    if (scale_num_ == 0) fail("no $timescale before $enddefinitions");
    if (signals_.empty()) fail("no 1-bit or vector variables declared");
  }

  void timescale() {
    // A second one would change the meaning of every time stamp: which was meant is not known.
    if (scale_num_ != 0) fail("a second $timescale (the first: " + timescale_ + ")");
    std::string text;
    for (std::string t = token("the timescale"); t != "$end"; t = token("$end of $timescale")) text += t;
    std::size_t digits = 0;
    while (digits < text.size() && std::isdigit(static_cast<unsigned char>(text[digits]))) ++digits;
    const std::string number = text.substr(0, digits), unit = text.substr(digits);
    static const std::map<std::string, std::int64_t> kFs{{"s", 1'000'000'000'000'000}, {"ms", 1'000'000'000'000},
                                                         {"us", 1'000'000'000},        {"ns", 1'000'000},
                                                         {"ps", 1'000},                {"fs", 1}};
    const auto u = kFs.find(unit);
    if ((number != "1" && number != "10" && number != "100") || u == kFs.end())
      fail("unknown $timescale '" + text.substr(0, 40) + "': expected 1, 10 or 100 followed by s, ms, us, ns, ps or fs");
    // Time per unit in femtoseconds as a fraction of a picosecond: ps = t * num / 1000.
    scale_num_ = std::stoll(number) * u->second;
    resolution_ = Time{std::max<std::int64_t>(1, scale_num_ / 1000)};
    timescale_ = number + " " + unit;
  }

  void variable() {
    const std::string type = token("the variable's type");
    const std::string width_text = token("the variable's width");
    const std::string id = token("the variable's identifier");
    std::string name = token("the variable's name");
    std::string range;
    for (std::string t = token("$end of $var"); t != "$end"; t = token("$end of $var")) range += t;
    unsigned width = 0;
    const auto [p, ec] = std::from_chars(width_text.data(), width_text.data() + width_text.size(), width);
    if (ec != std::errc() || p != width_text.data() + width_text.size() || width == 0 || width > 4096)
      fail("variable '" + name + "': width '" + width_text + "' is not 1 .. 4096");
    std::string full;
    for (const auto& s : scopes_) full += s + ".";
    full += name;
    spend_on_names(name, width, full.size() + range.size());
    if (const auto it = vars_.find(id); it != vars_.end()) {
      if (!it->second.real) alias(it->second, name, bit_names(name, full, range, width));
      return;
    }
    Variable v;
    v.first = static_cast<std::uint32_t>(signals_.size());
    v.width = width;
    // Reals and GTKWave's text traces ("string") carry no logic level: read past, never signals.
    v.real = type == "real" || type == "realtime" || type == "string";
    if (!v.real) {
      const auto bits = bit_names(name, full, range, width);
      signals_.insert(signals_.end(), bits.begin(), bits.end());
    }
    const Variable& stored = vars_[id] = v;
    if (const auto slot = short_slot(id)) short_ids_[*slot] = &stored;
  }

  // Every declared bit is kept by its full name (scopes included), for the signal options to find:
  // a header of wide vectors or deep scopes could ask for gigabytes from a few kilobytes of file.
  // A budget on those names, far beyond any testbench's or logic analyzer's dump, ends it first.
  static constexpr std::size_t kMaxNameBytes = std::size_t{64} << 20;
  void spend_on_names(const std::string& name, unsigned width, std::size_t name_size) {
    // Each bit's name with its index ("[4095]") and what a string costs beside its characters.
    const std::size_t cost = std::size_t{width} * (name_size + 8 + sizeof(std::string));
    if (cost <= kMaxNameBytes - name_bytes_) {
      name_bytes_ += cost;
      return;
    }
    fail("variable '" + name.substr(0, 40) + "': the header declares more than its signals' names may take (" +
         std::to_string(kMaxNameBytes >> 20) + " MiB; " + std::to_string(signals_.size() + aliases_.size()) +
         " one-bit names so far): record the EnDat lines, not the whole design");
  }
  std::size_t name_bytes_ = 0;

  // The names of a variable's bits, most significant first: "data[3]" for a bit of a vector;
  // a 1-bit variable keeps its range. "[7:0]" after the name (or in it): the bits run from the
  // first index to the second.
  std::vector<std::string> bit_names(const std::string& name, const std::string& full_name, const std::string& given_range,
                                     unsigned width) const {
    std::string full = full_name, range = given_range;
    // GHDL writes a vector's range into its name: "bus[3:0]".
    if (const auto open = full.rfind('['); range.empty() && width > 1 && open != std::string::npos && full.back() == ']') {
      range = full.substr(open);
      full.erase(open);
    }
    long msb = static_cast<long>(width) - 1, lsb = 0;
    if (const auto open = range.find('['); !range.empty() && open != std::string::npos) {
      const auto colon = range.find(':');
      try {
        msb = std::stol(range.substr(open + 1));
        lsb = colon == std::string::npos ? msb : std::stol(range.substr(colon + 1));
      } catch (const std::exception&) {
        fail("variable '" + name + "': bad bit range '" + range + "'");
      }
    }
    const long span = static_cast<long>(width) - 1;
    if (msb >= lsb ? msb < LONG_MIN + span : msb > LONG_MAX - span)
      fail("variable '" + name + "': bit range '" + range + "' leaves no room for its " + std::to_string(width) + " bits");
    if (width == 1) return {range.empty() ? full : full + range};
    std::vector<std::string> out;
    const long step = msb >= lsb ? -1 : 1;
    for (unsigned i = 0; i < width; ++i) out.push_back(full + "[" + std::to_string(msb + step * static_cast<long>(i)) + "]");
    return out;
  }

  // An identifier declared again, under another scope or name, is the same signal (IEEE 1364
  // section 18; Icarus, Verilator and VCS declare a port and the net it connects so): each of its
  // bits gets the new name as an alias.
  void alias(const Variable& v, const std::string& name, const std::vector<std::string>& bits) {
    if (bits.size() != v.width)
      fail("variable '" + name + "': " + std::to_string(bits.size()) + " bits, but its identifier was declared first with " +
           std::to_string(v.width));
    for (std::uint32_t i = 0; i < v.width; ++i) aliases_.emplace_back(bits[i], v.first + i);
  }

  const std::vector<std::pair<std::string, std::uint32_t>>& aliases() const override { return aliases_; }

  // Identifiers of one or two printable characters (what writers give the first 8 000 variables)
  // have a slot of their own: a value change is looked up without hashing.
  static constexpr std::size_t kPrintable = '~' - '!' + 1;
  static std::optional<std::size_t> short_slot(std::string_view id) {
    const auto code = [](char c) -> std::optional<std::size_t> {
      if (c < '!' || c > '~') return std::nullopt;
      return static_cast<std::size_t>(c - '!');
    };
    if (id.size() == 1) return code(id[0]);
    if (id.size() != 2) return std::nullopt;
    const auto first = code(id[0]), second = code(id[1]);
    if (!first || !second) return std::nullopt;
    return kPrintable + *first * kPrintable + *second;
  }

  const Variable& lookup(std::string_view id) {
    if (const auto slot = short_slot(id); slot && short_ids_[*slot] != nullptr) return *short_ids_[*slot];
    const auto it = vars_.find(id);
    if (it == vars_.end()) fail("value change for undeclared identifier '" + std::string(id.substr(0, 40)) + "'");
    return it->second;
  }

  void emit(std::uint32_t signal, char value) { QueuedReader::emit(now_, signal, value); }

  // One token of the body; false at the end of the file.
  bool body_token() {
    std::string_view t;  // into the token stream's buffer: used before the next token is read
    if (!tokens_.next(t)) return false;
    if (t.size() > TokenStream::kMaxToken) fail("a token longer than " + std::to_string(TokenStream::kMaxToken) + " characters");
    if (tokens_.unterminated())
      fail("truncated: the file ends inside '" + quoted(t) + "', without the end of its line");
    switch (t[0]) {
      case '$':
        if (t == "$comment") skip_to_end(std::string(t));
        return true;  // $dumpvars, $dumpall, $dumpon, $dumpoff and their $end: the changes inside count
      case '#': {
        const std::optional<std::int64_t> units = decimal(t.substr(1));
        if (!units) fail("bad timestamp '" + quoted(t) + "'");
        if (*units > (INT64_MAX - 500) / scale_num_) fail("timestamp '" + quoted(t) + "' beyond the picosecond range");
        const Time at{(*units * scale_num_ + 500) / 1000};
        if ((*units * scale_num_) % 1000 != 0) rounded_ = true;
        if (at < now_) fail("time goes backwards (" + quoted(t) + ")");
        now_ = at;
        return true;
      }
      case 'b': case 'B': {
        const std::string digits(t.substr(1));  // before the next token replaces t
        vector(digits, token("the vector's identifier"));
        return true;
      }
      case 'r': case 'R': lookup(token("the real's identifier")); return true;
      case 's': case 'S': lookup(token("the text's identifier")); return true;
      default: break;
    }
    const char v = normalize(t[0]);
    if (v == '?' || t.size() < 2) fail("'" + quoted(t) + "' is no value change");
    const Variable& var = lookup(t.substr(1));
    if (var.real || var.width != 1) fail("scalar value '" + quoted(t) + "' for a vector or real variable");
    emit(var.first, v);
    return true;
  }

  // A token's first 40 characters, for a message.
  static std::string quoted(std::string_view t) { return std::string(t.substr(0, 40)); }

  // Digits only, at most INT64_MAX (a time stamp's units); nullopt for anything else. By hand, with
  // one check for the range at the end: std::from_chars took half of a time stamp's share of
  // reading a capture.
  static std::optional<std::int64_t> decimal(std::string_view digits) {
    if (digits.empty()) return std::nullopt;
    const std::size_t zeros = std::min(digits.find_first_not_of('0'), digits.size());
    if (digits.size() - zeros > 19) return std::nullopt;  // 10^19 > INT64_MAX
    std::uint64_t value = 0;  // 19 digits stay below 2^64
    for (const char c : digits) {
      const auto d = static_cast<unsigned>(c - '0');
      if (d > 9) return std::nullopt;
      value = value * 10 + d;
    }
    if (value > static_cast<std::uint64_t>(INT64_MAX)) return std::nullopt;
    return static_cast<std::int64_t>(value);
  }

  // "b0101 id": left-extended with 0, or with x when the leftmost digit is x or z.
  void vector(const std::string& digits, const std::string& id) {
    const Variable& var = lookup(id);
    if (var.real) return;
    if (digits.empty() || digits.size() > var.width) fail("vector value 'b" + digits.substr(0, 40) + "' does not fit '" + id + "'");
    const char fill = normalize(digits[0]) == 'x' ? 'x' : '0';
    const std::size_t pad = var.width - digits.size();
    for (unsigned i = 0; i < var.width; ++i) {
      const char v = i < pad ? fill : normalize(digits[i - pad]);
      if (v == '?') fail("'" + std::string(1, digits[i - pad]) + "' in vector value 'b" + digits.substr(0, 40) + "'");
      emit(var.first + i, v);
    }
  }

  // Identifiers looked up by a view into the token, with no string made per value change.
  struct IdHash {
    using is_transparent = void;
    std::size_t operator()(std::string_view id) const { return std::hash<std::string_view>{}(id); }
  };

  TokenStream tokens_;
  std::vector<std::string> scopes_;
  std::unordered_map<std::string, Variable, IdHash, std::equal_to<>> vars_;  // its elements never move
  std::vector<const Variable*> short_ids_ = std::vector<const Variable*>(kPrintable + kPrintable * kPrintable);
  std::vector<std::pair<std::string, std::uint32_t>> aliases_;  // further names of declared bits
  bool rounded_ = false;  // a time fell between two picoseconds
  std::int64_t scale_num_ = 0;  // femtoseconds per unit
  std::string timescale_;       // as the file gives it: "1 fs"
  Time now_{0};
};

}  // namespace

std::unique_ptr<Reader> open_vcd(const std::string& path) { return std::make_unique<VcdReader>(path); }

}  // namespace endatsim::capture

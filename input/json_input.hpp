#pragma once
// Untrusted JSON files — scenarios and encoder profiles — read the same way: a size limit and a
// reason when a file cannot be read; a parse that refuses what nlohmann::json would take silently
// (a key given twice, nesting without end, a NUL byte that hides what follows it); and typed
// accessors whose errors name the file, the JSON path and what was expected. Every error is an
// InputError whose message is complete; callers rethrow it as their own error type.

#include "endatsim/input/text.hpp"
#include "endatsim/sim/time.hpp"

#include <cstdint>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace endatsim::input {

using nlohmann::json;

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// What a file is expected to hold, for messages: "scenario", "encoder profile".
struct FileKind {
  std::string_view noun;
  std::string_view article;  // "a", "an"
};

inline constexpr std::size_t kMaxFileBytes = 4 << 20;
inline constexpr std::size_t kMaxDepth = 32;

// The bytes of the regular file `path`, at most kMaxFileBytes of them, not empty.
std::string read_file(const std::string& path, FileKind kind);

// `text` as JSON. Refuses nesting deeper than kMaxDepth, a key given twice in one object, a NUL
// byte anywhere and numbers out of range, each with the place.
json parse(const std::string& text, const std::string& file);

// A value in the document and its JSON path.
inline constexpr std::size_t kWordStringDigits = 16;

// The strings Node::as_word reads as a value in min .. max, as one ECMAScript regular expression:
// the JSON Schema's form of the check on keys such as addresses ("7", "0x07", "0X0007").
std::string word_string_pattern(std::uint64_t min, std::uint64_t max);

class Node {
 public:
  Node(const json& j, std::string path, const std::string& file) : j_(j), path_(std::move(path)), file_(file) {}

  [[noreturn]] void fail(const std::string& expected) const;  // "expected <expected>, got <value>"
  [[noreturn]] void fail_raw(const std::string& message) const;
  const json& raw() const { return j_; }
  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }
  Node child(const std::string& key) const;  // the key must exist
  Node item(std::size_t i) const;            // the index must exist

  std::string as_string() const;
  bool as_bool() const;
  std::uint64_t as_uint(std::uint64_t min, std::uint64_t max) const;
  std::int64_t as_int(std::int64_t min, std::int64_t max) const;
  double as_number(double min, double max, const std::string& unit) const;
  sim::Time as_duration(sim::Time min, sim::Time max) const;
  // `or_zero`: 0 is allowed besides min .. max.
  sim::Hertz as_frequency(sim::Hertz min, sim::Hertz max, bool or_zero = false) const;
  // An integer given as a number or as a string in hex ("0xA5B4") or decimal, of at most
  // kWordStringDigits digits (leading zeros allowed).
  std::uint64_t as_word(std::uint64_t max) const;
  // A 16-bit word written only as a hex string such as "0x8019" (memory images).
  std::uint16_t as_hex_word() const;
  template <class E>
  E as_enum(std::initializer_list<std::pair<std::string_view, E>> choices) const {
    if (j_.is_string())
      for (const auto& c : choices)
        if (c.first == j_.get_ref<const std::string&>()) return c.second;
    std::vector<std::string> names;
    for (const auto& c : choices) names.emplace_back(c.first);
    fail_choice(names);
  }
  // "expected one of \"a\", \"b\", got ..." with a "did you mean" for a near miss.
  [[noreturn]] void fail_choice(const std::vector<std::string>& names) const;

 private:
  const json& j_;
  std::string path_;
  const std::string& file_;
};

// An object whose keys must all be known: unknown keys are errors, not silently ignored.
class Object {
 public:
  explicit Object(const Node& n);
  std::optional<Node> opt(const std::string& key);
  Node req(const std::string& key);
  void done() const;  // throws for the first key that opt() or req() did not ask for
  const Node& node() const { return n_; }

 private:
  const Node& n_;
  std::set<std::string> known_;
};

}  // namespace endatsim::input

// A JSON value as a flat list of tokens, for the outputs written once per frame (the results
// file's frames, the transaction log and its JSON lines): built with one vector and no tree, and
// written straight into text, byte for byte as nlohmann::json's dump() writes the same value —
// in the order it was built (an ordered_json) or with each object's keys sorted (a json, whose
// objects are std::maps). What else wants a tree gets one (ordered(), sorted()).
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace endatsim::scenarios {

class JsonTokens {
 public:
  enum class Kind : std::uint8_t { BeginObject, EndObject, BeginArray, EndArray, Key, String, Int, UInt, Double, Bool, Null };
  struct Token {
    Kind kind;
    std::string text;         // a key or a string
    std::uint64_t bits = 0;   // an Int, UInt or Bool; a Double's bits
  };
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);

  JsonTokens& begin_object() { return add(Kind::BeginObject); }
  JsonTokens& end_object() { return add(Kind::EndObject); }
  JsonTokens& begin_array() { return add(Kind::BeginArray); }
  JsonTokens& end_array() { return add(Kind::EndArray); }
  // Inside an object, each value follows its key.
  JsonTokens& key(std::string_view k) { return add(Kind::Key, std::string(k)); }
  JsonTokens& value(std::string_view s) { return add(Kind::String, std::string(s)); }
  JsonTokens& value(std::string&& s) { return add(Kind::String, std::move(s)); }
  JsonTokens& value(const char* s) { return value(std::string_view(s)); }
  JsonTokens& value(bool b) { return add(Kind::Bool, {}, b ? 1 : 0); }
  JsonTokens& value(std::nullptr_t) { return add(Kind::Null); }
  JsonTokens& value(double d);
  template <class I>
    requires(std::is_integral_v<I> && !std::is_same_v<I, bool>)
  JsonTokens& value(I i) {
    if constexpr (std::is_signed_v<I>) return add(Kind::Int, {}, static_cast<std::uint64_t>(static_cast<std::int64_t>(i)));
    else return add(Kind::UInt, {}, static_cast<std::uint64_t>(i));
  }
  template <class V>
  JsonTokens& member(std::string_view k, V&& v) {
    key(k);
    return value(std::forward<V>(v));
  }

  // dump(-1): compact.
  std::string compact() const;
  void compact(std::string& out) const;
  // dump(2), each line after the first shifted right by `indent`, each object's keys sorted.
  void sorted_indented(std::string& out, std::size_t indent) const;
  nlohmann::ordered_json ordered() const;
  nlohmann::json sorted() const;

  // Reading the value back (the text log): the value of `key` in the object that begins at
  // `object` (npos when it has none), an object's members as (key token, value token), a token.
  std::size_t find(std::size_t object, std::string_view key) const;
  std::vector<std::pair<std::size_t, std::size_t>> members(std::size_t object) const;
  const Token& at(std::size_t token) const { return tokens_[token]; }
  // A scalar as dump() writes it.
  void scalar(std::string& out, std::size_t token) const;
  // The token after the value that begins at `token`.
  std::size_t end_of(std::size_t token) const;

 private:
  JsonTokens& add(Kind kind, std::string text = {}, std::uint64_t bits = 0) {
    tokens_.push_back(Token{kind, std::move(text), bits});
    return *this;
  }
  std::size_t write_compact(std::string& out, std::size_t token) const;
  std::size_t write_sorted(std::string& out, std::size_t token, std::size_t indent) const;
  template <class J>
  std::size_t build(J& out, std::size_t token) const;
  std::vector<Token> tokens_;
};

}  // namespace endatsim::scenarios

#include "endatsim/scenarios/json_tokens.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <stdexcept>

namespace endatsim::scenarios {
namespace {

using nlohmann::json;

// A string as dump() writes it (ensure_ascii off, invalid UTF-8 replaced): printable ASCII
// without '"' and '\' as it is, anything else through nlohmann's own escaping.
void put_string(std::string& out, std::string_view s) {
  const bool plain = std::all_of(s.begin(), s.end(), [](char c) {
    return c >= 0x20 && c < 0x7F && c != '"' && c != '\\';
  });
  if (!plain) {
    out += json(std::string(s)).dump(-1, ' ', false, json::error_handler_t::replace);
    return;
  }
  out += '"';
  out += s;
  out += '"';
}

template <class N>
void put_number(std::string& out, N n) {
  char text[24];
  const auto end = std::to_chars(text, text + sizeof text, n).ptr;
  out.append(text, end);
}

}  // namespace

JsonTokens& JsonTokens::value(double d) { return add(Kind::Double, {}, std::bit_cast<std::uint64_t>(d)); }

void JsonTokens::scalar(std::string& out, std::size_t token) const {
  const Token& t = tokens_[token];
  switch (t.kind) {
    case Kind::String: put_string(out, t.text); break;
    case Kind::Int: put_number(out, static_cast<std::int64_t>(t.bits)); break;
    case Kind::UInt: put_number(out, t.bits); break;
    case Kind::Double: out += json(std::bit_cast<double>(t.bits)).dump(); break;
    case Kind::Bool: out += t.bits != 0 ? "true" : "false"; break;
    case Kind::Null: out += "null"; break;
    default: throw std::logic_error("JsonTokens::scalar: not a scalar");
  }
}

std::size_t JsonTokens::end_of(std::size_t token) const {
  std::size_t depth = 0;
  do {
    const Kind k = tokens_[token].kind;
    if (k == Kind::BeginObject || k == Kind::BeginArray) ++depth;
    else if (k == Kind::EndObject || k == Kind::EndArray) --depth;
    ++token;
  } while (depth > 0);
  return token;
}

std::vector<std::pair<std::size_t, std::size_t>> JsonTokens::members(std::size_t object) const {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (std::size_t t = object + 1; tokens_[t].kind != Kind::EndObject; t = end_of(t + 1)) out.emplace_back(t, t + 1);
  return out;
}

std::size_t JsonTokens::find(std::size_t object, std::string_view key) const {
  for (std::size_t t = object + 1; tokens_[t].kind != Kind::EndObject; t = end_of(t + 1))
    if (tokens_[t].text == key) return t + 1;
  return npos;
}

std::string JsonTokens::compact() const {
  std::string out;
  compact(out);
  return out;
}

void JsonTokens::compact(std::string& out) const {
  if (!tokens_.empty()) write_compact(out, 0);
}

std::size_t JsonTokens::write_compact(std::string& out, std::size_t token) const {
  const Kind kind = tokens_[token].kind;
  if (kind != Kind::BeginObject && kind != Kind::BeginArray) {
    scalar(out, token);
    return token + 1;
  }
  const bool object = kind == Kind::BeginObject;
  out += object ? '{' : '[';
  std::size_t t = token + 1;
  for (bool first = true; tokens_[t].kind != Kind::EndObject && tokens_[t].kind != Kind::EndArray; first = false) {
    if (!first) out += ',';
    if (object) {
      put_string(out, tokens_[t].text);
      out += ':';
      ++t;
    }
    t = write_compact(out, t);
  }
  out += object ? '}' : ']';
  return t + 1;
}

void JsonTokens::sorted_indented(std::string& out, std::size_t indent) const {
  if (!tokens_.empty()) write_sorted(out, 0, indent);
}

std::size_t JsonTokens::write_sorted(std::string& out, std::size_t token, std::size_t indent) const {
  const Kind kind = tokens_[token].kind;
  if (kind != Kind::BeginObject && kind != Kind::BeginArray) {
    scalar(out, token);
    return token + 1;
  }
  const bool object = kind == Kind::BeginObject;
  // Each member or element: where its key (objects) and its value begin.
  std::vector<std::pair<std::size_t, std::size_t>> parts;
  std::size_t t = token + 1;
  while (tokens_[t].kind != Kind::EndObject && tokens_[t].kind != Kind::EndArray) {
    const std::size_t value = object ? t + 1 : t;
    parts.emplace_back(t, value);
    t = end_of(value);
  }
  if (parts.empty()) {
    out += object ? "{}" : "[]";
    return t + 1;
  }
  if (object)
    std::stable_sort(parts.begin(), parts.end(),
                     [&](const auto& a, const auto& b) { return tokens_[a.first].text < tokens_[b.first].text; });
  out += object ? "{\n" : "[\n";
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (i > 0) out += ",\n";
    out.append(indent + 2, ' ');
    if (object) {
      put_string(out, tokens_[parts[i].first].text);
      out += ": ";
    }
    write_sorted(out, parts[i].second, indent + 2);
  }
  out += '\n';
  out.append(indent, ' ');
  out += object ? '}' : ']';
  return t + 1;
}

template <class J>
std::size_t JsonTokens::build(J& out, std::size_t token) const {
  const Token& t = tokens_[token];
  switch (t.kind) {
    case Kind::BeginObject:
    case Kind::BeginArray: {
      const bool object = t.kind == Kind::BeginObject;
      out = object ? J::object() : J::array();
      std::size_t i = token + 1;
      while (tokens_[i].kind != Kind::EndObject && tokens_[i].kind != Kind::EndArray) {
        J element;
        if (object) {
          const std::string& key = tokens_[i].text;
          i = build(element, i + 1);
          out[key] = std::move(element);
        } else {
          i = build(element, i);
          out.push_back(std::move(element));
        }
      }
      return i + 1;
    }
    case Kind::String: out = t.text; break;
    case Kind::Int: out = static_cast<std::int64_t>(t.bits); break;
    case Kind::UInt: out = t.bits; break;
    case Kind::Double: out = std::bit_cast<double>(t.bits); break;
    case Kind::Bool: out = t.bits != 0; break;
    case Kind::Null: out = nullptr; break;
    default: throw std::logic_error("JsonTokens: a value was expected");
  }
  return token + 1;
}

nlohmann::ordered_json JsonTokens::ordered() const {
  nlohmann::ordered_json out;
  if (!tokens_.empty()) build(out, 0);
  return out;
}

nlohmann::json JsonTokens::sorted() const {
  json out;
  if (!tokens_.empty()) build(out, 0);
  return out;
}

}  // namespace endatsim::scenarios

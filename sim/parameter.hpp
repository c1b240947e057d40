#pragma once
// A model's named parameters as data, one row per scenario key, the way the checker keeps its
// timing table: the key, the field it sets, its range, the D297403 section the range or meaning
// comes from, and a help text. The scenario loader reads the keys through these rows, the model
// checks its ranges with them, and the JSON Schema's properties and docs/parameters.md are
// generated from them, so a range is written once.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "endatsim/sim/time.hpp"

namespace endatsim::sim {

// A choice between named behaviours (an enum field), reached through its index in `names`.
template <class Params>
struct ChoiceField {
  std::span<const std::string_view> names;
  std::size_t (*get)(const Params&);
  void (*set)(Params&, std::size_t);
};

template <class Params>
struct Parameter {
  // Durations (min/max in ps), counts, flags, 16-bit words (max only), choices.
  using Field = std::variant<Time Params::*, std::optional<Time> Params::*, unsigned Params::*,
                             std::optional<std::uint64_t> Params::*, bool Params::*, std::uint16_t Params::*,
                             ChoiceField<Params>>;
  std::string_view key;
  Field field;
  std::int64_t min = 0, max = 0;
  std::string_view section;  // where D297403 gives the range or meaning; "" for the model's own choice
  std::string_view help;
};

enum class ParameterType : std::uint8_t { Duration, Count, Flag, Word, Choice };

template <class Params>
ParameterType type_of(const Parameter<Params>& p) {
  switch (p.field.index()) {
    case 0:
    case 1: return ParameterType::Duration;
    case 2:
    case 3: return ParameterType::Count;
    case 4: return ParameterType::Flag;
    case 5: return ParameterType::Word;
    default: return ParameterType::Choice;
  }
}

// "10 .. 30 us", "1 .. 48", "0 .. 65535", "\"a\" | \"b\"", "true | false".
template <class Params>
std::string range_text(const Parameter<Params>& p) {
  switch (type_of(p)) {
    case ParameterType::Duration: {
      // "10 .. 30 us", "0 .. 100 ms", "200 ns .. 10 ms": one unit where both share it
      const std::string lo = format_time(Time{p.min}), hi = format_time(Time{p.max});
      const auto unit = [](const std::string& t) { return t.substr(t.rfind(' ') + 1); };
      if (p.min == 0) return "0 .. " + hi;
      if (unit(lo) == unit(hi)) return lo.substr(0, lo.rfind(' ')) + " .. " + hi;
      return lo + " .. " + hi;
    }
    case ParameterType::Count: return std::to_string(p.min) + " .. " + std::to_string(p.max);
    case ParameterType::Flag: return "true | false";
    case ParameterType::Word: return "0 .. " + std::to_string(p.max);
    case ParameterType::Choice: break;
  }
  std::string s;
  for (const auto name : std::get<ChoiceField<Params>>(p.field).names) s += (s.empty() ? "\"" : " | \"") + std::string(name) + "\"";
  return s;
}

// The field's value in `params` as a scenario writes it; "none" for an unset optional.
template <class Params>
std::string value_text(const Parameter<Params>& p, const Params& params) {
  struct Visitor {
    const Params& params;
    std::string operator()(Time Params::*f) const { return format_time(params.*f); }
    std::string operator()(std::optional<Time> Params::*f) const {
      return (params.*f) ? format_time(*(params.*f)) : "none";
    }
    std::string operator()(unsigned Params::*f) const { return std::to_string(params.*f); }
    std::string operator()(std::optional<std::uint64_t> Params::*f) const {
      return (params.*f) ? std::to_string(*(params.*f)) : "none";
    }
    std::string operator()(bool Params::*f) const { return params.*f ? "true" : "false"; }
    std::string operator()(std::uint16_t Params::*f) const { return std::to_string(params.*f); }
    std::string operator()(const ChoiceField<Params>& c) const { return "\"" + std::string(c.names[c.get(params)]) + "\""; }
  };
  return std::visit(Visitor{params}, p.field);
}

// Why the field's value in `params` lies outside the row's range, or none: "t_m must be
// 10 us .. 30 us (2.3.2), got 5 us". `owner` names the model ("encoder").
template <class Params>
std::optional<std::string> out_of_range(const Parameter<Params>& p, const Params& params, std::string_view owner) {
  bool inside = true;
  if (const auto* f = std::get_if<Time Params::*>(&p.field)) {
    inside = (params.**f).count() >= p.min && (params.**f).count() <= p.max;
  } else if (const auto* g = std::get_if<std::optional<Time> Params::*>(&p.field)) {
    inside = !(params.**g) || ((params.**g)->count() >= p.min && (params.**g)->count() <= p.max);
  } else if (const auto* u = std::get_if<unsigned Params::*>(&p.field)) {
    inside = static_cast<std::int64_t>(params.**u) >= p.min && static_cast<std::int64_t>(params.**u) <= p.max;
  } else if (const auto* o = std::get_if<std::optional<std::uint64_t> Params::*>(&p.field)) {
    inside = !(params.**o) || (*(params.**o) >= static_cast<std::uint64_t>(p.min) && *(params.**o) <= static_cast<std::uint64_t>(p.max));
  }
  if (inside) return std::nullopt;
  return std::string(owner) + " " + std::string(p.key) + " must be " + range_text(p) +
         (p.section.empty() ? std::string() : " (" + std::string(p.section) + ")") + ", got " + value_text(p, params);
}

}  // namespace endatsim::sim

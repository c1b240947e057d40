#pragma once
// A model's named parameters as data, one row per scenario key, the way the checker keeps its
// timing table: the key, the field it sets, its range, the D297403 section the range or meaning
// comes from, and a help text. The scenario loader reads the keys through these rows, the model
// checks its ranges with them, and the JSON Schema's properties and docs/parameters.md are
// generated from them, so a range is written once (docs/parameters.md names the few keys that are
// not rows).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>

#include "endatsim/sim/time.hpp"

namespace endatsim::sim {

// A duration as a row's bound: whole picoseconds.
constexpr std::int64_t row_bound(Time t) { return t.count(); }

// How a model refuses parameters it cannot run with: std::invalid_argument with `message`.
inline void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

// A choice between named behaviours (an enum field), reached through its index in `names`.
template <class Params>
struct ChoiceField {
  std::span<const std::string_view> names;
  std::size_t (*get)(const Params&);
  void (*set)(Params&, std::size_t);
};

// The ChoiceField of an enum member whose values are 0, 1, ... in the order of `names`.
template <class Params, auto Field, const auto& Names>
constexpr ChoiceField<Params> enum_choice() {
  using E = std::remove_cvref_t<decltype(std::declval<Params&>().*Field)>;
  return {Names, [](const Params& p) { return static_cast<std::size_t>(p.*Field); },
          [](Params& p, std::size_t i) { p.*Field = static_cast<E>(i); }};
}

// A frequency (Hertz is an integer type, so it is told apart from a count by this wrapper).
template <class Params>
struct FrequencyField {
  Hertz Params::*field;
};

// A plain number with a unit, such as a cable length in metres.
template <class Params>
struct NumberField {
  double Params::*field;
  std::string_view unit;  // as a message writes it after the number: " m"
};

template <class Params>
struct Parameter {
  // Durations and frequencies (min/max in ps or Hz), numbers, counts, flags, words (max only),
  // choices.
  using Field =
      std::variant<Time Params::*, std::optional<Time> Params::*, FrequencyField<Params>, NumberField<Params>,
                   unsigned Params::*, std::optional<std::uint64_t> Params::*, std::uint64_t Params::*,
                   std::int64_t Params::*, int Params::*, bool Params::*, std::uint16_t Params::*, std::uint8_t Params::*,
                   ChoiceField<Params>>;
  std::string_view key;
  Field field;
  std::int64_t min = 0, max = 0;
  std::string_view section;  // where D297403 gives the range or meaning; "" for the model's own choice
  std::string_view help;
  bool required = false;     // the key must be given (no default applies)
  bool zero_allowed = false; // 0 is allowed besides min .. max (it means what the help says)
  // What applies when the key is not given, where that is not the field's value in the defaults
  // ("one period of the master's f_c"); empty: the value in the defaults.
  std::string_view default_text = {};
};

enum class ParameterType : std::uint8_t { Duration, Frequency, Number, Count, Flag, Word, Choice };

template <class Params>
ParameterType type_of(const Parameter<Params>& p) {
  static_assert(std::variant_size_v<typename Parameter<Params>::Field> == 13, "a new kind of field needs its type here");
  switch (p.field.index()) {
    case 0:
    case 1: return ParameterType::Duration;
    case 2: return ParameterType::Frequency;
    case 3: return ParameterType::Number;
    case 4:
    case 5:
    case 6:
    case 7:
    case 8: return ParameterType::Count;
    case 9: return ParameterType::Flag;
    case 10:
    case 11: return ParameterType::Word;
    default: return ParameterType::Choice;
  }
}

// "10 .. 30 us", "100 kHz .. 16 MHz", "1 .. 48", "0 .. 65535", "\"a\" | \"b\"", "true | false".
template <class Params>
std::string range_text(const Parameter<Params>& p) {
  if (p.zero_allowed && p.min > 0) {
    Parameter<Params> nonzero = p;
    nonzero.zero_allowed = false;
    return "0 or " + range_text(nonzero);
  }
  switch (type_of(p)) {
    case ParameterType::Duration: return format_time_range(Time{p.min}, Time{p.max});
    case ParameterType::Frequency: return format_frequency_range(p.min, p.max);
    case ParameterType::Number:
      return std::to_string(p.min) + " .. " + std::to_string(p.max) + std::string(std::get<NumberField<Params>>(p.field).unit);
    case ParameterType::Count: return std::to_string(p.min) + " .. " + std::to_string(p.max);
    case ParameterType::Flag: return "true | false";
    case ParameterType::Word: return "0 .. " + std::to_string(p.max);
    case ParameterType::Choice: break;
  }
  std::string s;
  for (const auto name : std::get<ChoiceField<Params>>(p.field).names) s += (s.empty() ? "\"" : " | \"") + std::string(name) + "\"";
  return s;
}

namespace parameter_detail {
// The field's value as a number for the range check; none for an unset optional, a flag, a word
// or a choice (their type bounds them).
template <class Params>
std::optional<long double> numeric(const Parameter<Params>& p, const Params& params) {
  struct Visitor {
    const Params& params;
    std::optional<long double> operator()(Time Params::*f) const { return (params.*f).count(); }
    std::optional<long double> operator()(std::optional<Time> Params::*f) const {
      if (!(params.*f)) return std::nullopt;
      return (params.*f)->count();
    }
    std::optional<long double> operator()(const FrequencyField<Params>& f) const { return params.*f.field; }
    std::optional<long double> operator()(const NumberField<Params>& f) const { return params.*f.field; }
    std::optional<long double> operator()(unsigned Params::*f) const { return params.*f; }
    std::optional<long double> operator()(std::optional<std::uint64_t> Params::*f) const {
      if (!(params.*f)) return std::nullopt;
      return static_cast<long double>(*(params.*f));
    }
    std::optional<long double> operator()(std::uint64_t Params::*f) const { return static_cast<long double>(params.*f); }
    std::optional<long double> operator()(std::int64_t Params::*f) const { return static_cast<long double>(params.*f); }
    std::optional<long double> operator()(int Params::*f) const { return params.*f; }
    std::optional<long double> operator()(bool Params::*) const { return std::nullopt; }
    std::optional<long double> operator()(std::uint16_t Params::*) const { return std::nullopt; }
    std::optional<long double> operator()(std::uint8_t Params::*) const { return std::nullopt; }
    std::optional<long double> operator()(const ChoiceField<Params>&) const { return std::nullopt; }
  };
  return std::visit(Visitor{params}, p.field);
}
}  // namespace parameter_detail

// The field's value in `params` as a scenario writes it; "none" for an unset optional.
template <class Params>
std::string value_text(const Parameter<Params>& p, const Params& params) {
  struct Visitor {
    const Params& params;
    std::string operator()(Time Params::*f) const { return format_time(params.*f); }
    std::string operator()(std::optional<Time> Params::*f) const {
      return (params.*f) ? format_time(*(params.*f)) : "none";
    }
    std::string operator()(const FrequencyField<Params>& f) const { return format_frequency(params.*f.field); }
    std::string operator()(const NumberField<Params>& f) const {
      std::string s = std::to_string(params.*f.field);
      s.erase(s.find_last_not_of('0') + 1);  // 10.000000 -> 10.
      if (!s.empty() && s.back() == '.') s.pop_back();
      return s + std::string(f.unit);
    }
    std::string operator()(unsigned Params::*f) const { return std::to_string(params.*f); }
    std::string operator()(std::optional<std::uint64_t> Params::*f) const {
      return (params.*f) ? std::to_string(*(params.*f)) : "none";
    }
    std::string operator()(std::uint64_t Params::*f) const { return std::to_string(params.*f); }
    std::string operator()(std::int64_t Params::*f) const { return std::to_string(params.*f); }
    std::string operator()(int Params::*f) const { return std::to_string(params.*f); }
    std::string operator()(bool Params::*f) const { return params.*f ? "true" : "false"; }
    std::string operator()(std::uint16_t Params::*f) const { return std::to_string(params.*f); }
    std::string operator()(std::uint8_t Params::*f) const { return std::to_string(params.*f); }
    std::string operator()(const ChoiceField<Params>& c) const { return "\"" + std::string(c.names[c.get(params)]) + "\""; }
  };
  return std::visit(Visitor{params}, p.field);
}

// Why the field's value in `params` lies outside the row's range, or none: "encoder t_m must be
// 10 .. 30 us (2.3.2), got 5 us". `owner` names the model and object ("encoder", "master careful").
template <class Params>
std::optional<std::string> out_of_range(const Parameter<Params>& p, const Params& params, std::string_view owner) {
  const auto v = parameter_detail::numeric(p, params);
  // A NaN compares false both ways: outside.
  if (!v || (*v >= static_cast<long double>(p.min) && *v <= static_cast<long double>(p.max))) return std::nullopt;
  if (p.zero_allowed && *v == 0) return std::nullopt;
  return std::string(owner) + " " + std::string(p.key) + " must be " + range_text(p) +
         (p.section.empty() ? std::string() : " (" + std::string(p.section) + ")") + ", got " + value_text(p, params);
}

// The first row of `rows` whose value lies outside its range, as out_of_range() words it.
template <class Params>
std::optional<std::string> first_out_of_range(std::span<const Parameter<Params>> rows, const Params& params,
                                              std::string_view owner) {
  for (const auto& row : rows)
    if (auto why = out_of_range(row, params, owner)) return why;
  return std::nullopt;
}

}  // namespace endatsim::sim

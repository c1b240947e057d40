#pragma once
// Reading a model's parameter rows (sim/parameter.hpp) from a JSON object: each key present is
// read with the type and range its row gives, and an error names the file, the JSON path and
// what was expected.

#include <span>
#include <string>
#include <type_traits>
#include <variant>

#include "endatsim/input/json_input.hpp"
#include "endatsim/sim/parameter.hpp"

namespace endatsim::input {

template <class Params>
void read_parameter(const Node& v, const sim::Parameter<Params>& row, Params& p) {
  using sim::Time;
  const auto lo = static_cast<std::uint64_t>(row.min), hi = static_cast<std::uint64_t>(row.max);
  std::visit(
      [&](const auto& field) {
        using F = std::decay_t<decltype(field)>;
        if constexpr (std::is_same_v<F, Time Params::*> || std::is_same_v<F, std::optional<Time> Params::*>) {
          p.*field = v.as_duration(Time{row.min}, Time{row.max});
        } else if constexpr (std::is_same_v<F, sim::FrequencyField<Params>>) {
          p.*field.field = v.as_frequency(row.min, row.max, row.zero_allowed);
        } else if constexpr (std::is_same_v<F, sim::NumberField<Params>>) {
          p.*field.field = v.as_number(static_cast<double>(row.min), static_cast<double>(row.max), std::string(field.unit));
        } else if constexpr (std::is_same_v<F, unsigned Params::*>) {
          p.*field = static_cast<unsigned>(v.as_uint(lo, hi));
        } else if constexpr (std::is_same_v<F, std::optional<std::uint64_t> Params::*> ||
                             std::is_same_v<F, std::uint64_t Params::*>) {
          p.*field = v.as_uint(lo, hi);
        } else if constexpr (std::is_same_v<F, std::int64_t Params::*>) {
          p.*field = v.as_int(row.min, row.max);
        } else if constexpr (std::is_same_v<F, int Params::*>) {
          p.*field = static_cast<int>(v.as_int(row.min, row.max));  // rows of int fields keep within int
        } else if constexpr (std::is_same_v<F, bool Params::*>) {
          p.*field = v.as_bool();
        } else if constexpr (std::is_same_v<F, std::uint16_t Params::*>) {
          p.*field = static_cast<std::uint16_t>(v.as_word(hi));
        } else if constexpr (std::is_same_v<F, std::uint8_t Params::*>) {
          p.*field = static_cast<std::uint8_t>(v.as_word(hi));
        } else {
          static_assert(std::is_same_v<F, sim::ChoiceField<Params>>);
          if (v.raw().is_string())
            for (std::size_t i = 0; i < field.names.size(); ++i)
              if (field.names[i] == v.raw().template get_ref<const std::string&>()) return field.set(p, i);
          v.fail_choice(std::vector<std::string>(field.names.begin(), field.names.end()));
        }
      },
      row.field);
}

// Every row whose key the object holds, in the rows' order; a required key must be there.
template <class Params>
void read_parameters(Object& o, std::span<const sim::Parameter<Params>> rows, Params& p) {
  for (const auto& row : rows) {
    if (row.required) read_parameter(o.req(std::string(row.key)), row, p);
    else if (auto v = o.opt(std::string(row.key))) read_parameter(*v, row, p);
  }
}

}  // namespace endatsim::input

#pragma once
// A table of rows looked up by an enumerator's value (row = table[static_cast<size_t>(e)]) must
// list one row per enumerator in the enum's order: checked when it is compiled.

#include <cstddef>

namespace endatsim::protocol {

// Row i names enumerator i (its `member`), and there is a row for every enumerator up to `last`.
template <class Table, class Row, class Enum>
constexpr bool indexed_by(const Table& table, Enum Row::*member, Enum last) {
  if (table.size() != static_cast<std::size_t>(last) + 1) return false;
  for (std::size_t i = 0; i < table.size(); ++i)
    if (static_cast<std::size_t>(table[i].*member) != i) return false;
  return true;
}

// A list of enumerators names each one once, in the enum's order, up to `last`.
template <class List, class Enum>
constexpr bool lists_in_order(const List& list, Enum last) {
  if (list.size() != static_cast<std::size_t>(last) + 1) return false;
  for (std::size_t i = 0; i < list.size(); ++i)
    if (static_cast<std::size_t>(list[i]) != i) return false;
  return true;
}

}  // namespace endatsim::protocol

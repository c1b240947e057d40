#pragma once
// Fixed-width hexadecimal, as every report writes words and bytes: the spec's own notation
// (0000h, D297403 3.5) in texts and the C notation (0x0000) in JSON and expectations.

#include <cstdint>
#include <string>

namespace endatsim::sim {

// The `digits` lowest hexadecimal digits of `value`, upper case, padded with zeros.
inline std::string hex_digits(std::uint64_t value, int digits) {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  std::string s(static_cast<std::size_t>(digits), '0');
  for (int i = digits - 1; i >= 0; --i, value >>= 4) s[static_cast<std::size_t>(i)] = kDigits[value & 0xF];
  return s;
}

// "002Ah": the spec's notation.
inline std::string hex_h(std::uint64_t value, int digits) { return hex_digits(value, digits) + "h"; }

// "0x002A": the C notation.
inline std::string hex_0x(std::uint64_t value, int digits) { return "0x" + hex_digits(value, digits); }

}  // namespace endatsim::sim

#pragma once
// Small text helpers every reader and report shares: fixed-width hexadecimal, as the reports
// write words and bytes (the spec's own notation 0000h, D297403 3.5, in texts; 0x0000 in JSON and
// expectations), white space trimmed, a whole decimal number read exactly.

#include <cctype>
#include <charconv>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

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

// `text` without leading and trailing white space.
inline std::string_view trim(std::string_view text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) text.remove_prefix(1);
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.remove_suffix(1);
  return text;
}

// A whole decimal number and nothing else ("12"; not "", "+12", "12 " or "1e3").
inline std::optional<std::uint64_t> whole_number(std::string_view text) {
  std::uint64_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc{} || end != text.data() + text.size()) return std::nullopt;
  return v;
}

}  // namespace endatsim::sim

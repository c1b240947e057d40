#include "endatsim/sim/time.hpp"
#include "endatsim/sim/text.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <stdexcept>
#include <utility>

namespace endatsim::sim {
namespace {

using Wide = __int128;

struct Unit {
  std::string_view name;
  std::int64_t scale;
};

constexpr std::array kTimeUnits{Unit{"ps", 1}, Unit{"ns", 1'000}, Unit{"us", 1'000'000},
                                Unit{"ms", 1'000'000'000}, Unit{"s", 1'000'000'000'000}};
constexpr std::array kFrequencyUnits{Unit{"Hz", 1}, Unit{"kHz", 1'000}, Unit{"MHz", 1'000'000},
                                     Unit{"GHz", 1'000'000'000}};

// Parses "<decimal> <unit>" exactly into an integer number of base units.
template <std::size_t N>
std::int64_t parse_quantity(std::string_view text, const std::array<Unit, N>& units,
                            std::string_view what) {
  constexpr int kMaxFractionDigits = 20;
  const std::string expected = std::string("a ") + std::string(what) + " such as \"" +
                               (what == "duration" ? "2.5 us" : "2 MHz") + "\"";
  std::string_view s = trim(text);
  std::size_t i = 0;
  Wide mantissa = 0;
  int fraction_digits = 0;
  bool digits = false;
  bool point = false;
  for (; i < s.size(); ++i) {
    const char c = s[i];
    if (std::isdigit(static_cast<unsigned char>(c))) {
      digits = true;
      mantissa = mantissa * 10 + (c - '0');
      if (point && ++fraction_digits > kMaxFractionDigits)
        throw std::invalid_argument("expected " + expected + ", got more than " + std::to_string(kMaxFractionDigits) +
                                    " digits after the decimal point");
      if (mantissa > Wide{1} << 86) throw ValueTooLarge("expected " + expected + ", got a number too large");
    } else if (c == '.' && !point) {
      point = true;
    } else {
      break;
    }
  }
  if (!digits) throw std::invalid_argument("expected " + expected + ", got \"" + std::string(text) + "\"");
  const std::string_view unit = trim(s.substr(i));
  for (const Unit& u : units) {
    if (u.name != unit) continue;
    // mantissa <= 2^86 and scale <= 10^12 < 2^40: the product fits the 127 bits of Wide; the
    // divisor is at most 10^20.
    Wide value = mantissa * u.scale;
    Wide divisor = 1;
    for (int d = 0; d < fraction_digits; ++d) divisor *= 10;
    if (value % divisor != 0)
      throw std::invalid_argument("expected " + expected + " that is a whole number of " +
                                  std::string(units.front().name) + ", got \"" + std::string(text) + "\"");
    value /= divisor;
    if (value > Wide{INT64_MAX} / 2)
      throw ValueTooLarge("expected " + expected + ", got \"" + std::string(text) + "\" which is too large");
    return static_cast<std::int64_t>(value);
  }
  std::string names;
  for (const Unit& u : units) names += (names.empty() ? "" : ", ") + std::string(u.name);
  // The two mistakes people make most: a micro sign from a datasheet, and the wrong case.
  std::string hint;
  const bool micro = unit.find("\xC2\xB5") != std::string_view::npos || unit.find("\xCE\xBC") != std::string_view::npos;
  if (micro) hint = " (units are ASCII: write u for the micro sign, as in \"2.5 us\")";
  for (const Unit& u : units)
    if (!micro && unit.size() == u.name.size() &&
        std::equal(unit.begin(), unit.end(), u.name.begin(), [](char a, char b) {
          return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
        }))
      hint = " (units are case-sensitive: did you mean \"" + std::string(u.name) + "\"?)";
  throw std::invalid_argument("expected " + expected + " with a unit (" + names + "), got \"" + std::string(text) + "\"" +
                              hint);
}

std::string format_scaled(std::int64_t value, std::int64_t scale, std::string_view unit) {
  const bool negative = value < 0;
  const std::uint64_t v = negative ? 0 - static_cast<std::uint64_t>(value) : static_cast<std::uint64_t>(value);
  const auto s = static_cast<std::uint64_t>(scale);
  std::string out = negative ? "-" : "";
  out += std::to_string(v / s);
  std::uint64_t rest = v % s;
  if (rest != 0) {
    std::string frac;
    for (std::uint64_t div = s / 10; div > 0; div /= 10) {
      frac += static_cast<char>('0' + (rest / div) % 10);
    }
    while (!frac.empty() && frac.back() == '0') frac.pop_back();
    out += "." + frac;
  }
  return out + " " + std::string(unit);
}

template <std::size_t N>
std::string format_quantity(std::int64_t value, const std::array<Unit, N>& units) {
  const std::uint64_t mag = value < 0 ? 0 - static_cast<std::uint64_t>(value) : static_cast<std::uint64_t>(value);
  const Unit* best = &units.front();
  for (const Unit& u : units)
    if (mag >= static_cast<std::uint64_t>(u.scale)) best = &u;
  return format_scaled(value, best->scale, best->name);
}

}  // namespace

Time period_of(Hertz f) {
  if (f <= 0) throw std::invalid_argument("frequency must be positive");
  return Time{(kPsPerSecond + f / 2) / f};
}

Hertz frequency_of(Time t) {
  if (t.count() <= 0) throw std::invalid_argument("period must be positive");
  return (kPsPerSecond + t.count() / 2) / t.count();
}

Time parse_duration(std::string_view text) { return Time{parse_quantity(text, kTimeUnits, "duration")}; }

Hertz parse_frequency(std::string_view text) { return parse_quantity(text, kFrequencyUnits, "frequency"); }

std::string format_time(Time t) { return format_quantity(t.count(), kTimeUnits); }

std::string format_frequency(Hertz f) { return format_quantity(f, kFrequencyUnits); }

namespace {
std::string span_text(const std::string& lo, const std::string& hi, bool lo_zero) {
  const auto unit = [](const std::string& t) { return t.substr(t.rfind(' ') + 1); };
  if (lo_zero) return "0 .. " + hi;
  if (unit(lo) == unit(hi)) return lo.substr(0, lo.rfind(' ')) + " .. " + hi;
  return lo + " .. " + hi;
}
}  // namespace

std::string format_time_range(Time lo, Time hi) { return span_text(format_time(lo), format_time(hi), lo.count() == 0); }

std::string format_frequency_range(Hertz lo, Hertz hi) {
  return span_text(format_frequency(lo), format_frequency(hi), lo == 0);
}

}  // namespace endatsim::sim

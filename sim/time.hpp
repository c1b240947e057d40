// Simulation time: integer picoseconds. Nothing in the model uses floating-point time.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <stdexcept>
#include <string_view>

namespace endatsim::sim {

using Time = std::chrono::duration<std::int64_t, std::pico>;

inline constexpr std::int64_t kPsPerSecond = 1'000'000'000'000;
constexpr Time ps(std::int64_t v) { return Time{v}; }
constexpr Time ns(std::int64_t v) { return Time{v * 1'000}; }
constexpr Time us(std::int64_t v) { return Time{v * 1'000'000}; }
constexpr Time ms(std::int64_t v) { return Time{v * 1'000'000'000}; }

// Frequencies are whole hertz.
using Hertz = std::int64_t;
constexpr Hertz kHz(std::int64_t v) { return v * 1'000; }
constexpr Hertz MHz(std::int64_t v) { return v * 1'000'000; }

// The period of f, rounded to the nearest picosecond.
Time period_of(Hertz f);
// The frequency whose period is t, rounded to the nearest hertz.
Hertz frequency_of(Time t);

// "2 us", "500ns", "1.25 us", "0.000001 s": exact decimal parsing, no floating point.
// Throws std::invalid_argument with a message that says what was expected; ValueTooLarge (one
// kind of it) for a value beyond what an int64 of picoseconds or hertz holds, which a caller with
// a range of its own may name instead.
class ValueTooLarge : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};
Time parse_duration(std::string_view text);
// "2 MHz", "200 kHz", "16000000 Hz".
Hertz parse_frequency(std::string_view text);

// Human-readable, exact: "1.25 us", "62.5 ns", "7 ps".
std::string format_time(Time t);
std::string format_frequency(Hertz f);
// A range with its unit once where both ends share it: "80 .. 120 ms", "0 .. 1 us", "200 ns .. 10 ms".
std::string format_time_range(Time lo, Time hi);
std::string format_frequency_range(Hertz lo, Hertz hi);

}  // namespace endatsim::sim

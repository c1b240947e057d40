#pragma once
// A 128-bit signed integer for products of picosecond times and counts that overflow 64 bits
// (least-squares sums, positions unwrapped over many turns). GCC and Clang's __int128, marked as
// the extension it is, so that a user's -Wpedantic build including our headers stays quiet.

#include <cstdint>

#include "endatsim/sim/time.hpp"

namespace endatsim::sim {

__extension__ typedef __int128 Int128;

// x / d rounded toward minus infinity (d > 0): the step, revolution or range x lies in.
constexpr Int128 floor_div(Int128 x, Int128 d) { return x >= 0 ? x / d : -((-x + d - 1) / d); }

// The whole counts a rate of `per_second` has made after `picoseconds`, toward minus infinity: a
// moving axis counts a step when it crosses it, whichever way it moves.
constexpr Int128 counts_after(std::int64_t per_second, std::int64_t picoseconds) {
  return floor_div(static_cast<Int128>(per_second) * picoseconds, kPsPerSecond);
}

}  // namespace endatsim::sim

#pragma once
// The bounds of the scenario keys that hold lists, maps or values in a form of their own (the keys
// docs/parameters.md names as not rows): the loader checks them and the JSON Schema's properties
// for them are generated from these same constants (scenarios/parameter_docs.hpp), so that each
// bound is written once. Bounds the spec gives live in protocol/ and are used from there.

#include <cstddef>
#include <cstdint>

#include "endatsim/sim/time.hpp"

namespace endatsim::scenarios::list_keys {

// encoder.reference_marks: at most this many marks (the model's bound).
inline constexpr std::size_t kReferenceMarksMax = 1024;
// bus: further encoders on the line (2.10; the model's bound); expect.memory[].encoder counts
// them from 1 (0: the scenario's encoder).
inline constexpr std::size_t kBusEncodersMax = 31;
// expect.delay_measurement.max_error: a duration up to this, or "T/8".
inline constexpr sim::Time kDelayErrorMax = sim::us(10);
// A temperature in 0.1 K steps, as 3.9.6 scales it in a 16-bit word.
inline constexpr std::uint16_t kTemperatureMax = 0xFFFF;

}  // namespace endatsim::scenarios::list_keys

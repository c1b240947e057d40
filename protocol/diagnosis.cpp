#include "endatsim/protocol/diagnosis.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace endatsim::protocol::diagnosis {

std::string temperature_string(unsigned tenth_kelvin) {
  char text[48];
  std::snprintf(text, sizeof text, "%.1f degC (%.1f K)", celsius(tenth_kelvin), kelvin(tenth_kelvin));
  return text;
}

std::string kelvin_string(unsigned tenth_kelvin) {
  char text[24];
  std::snprintf(text, sizeof text, "%.1f K", kelvin(tenth_kelvin));
  return text;
}

long tenth_kelvin_of_celsius(double celsius) { return std::lround(celsius * 10.0) + kZeroCelsiusTenthKelvin; }

std::optional<double> temperature_scaling(std::uint16_t word4) {
  if ((word4 & 0x0007) == 0) return 0.1;
  return std::nullopt;
}

std::uint16_t encode_additional_sensor(unsigned address, unsigned tenth_kelvin) {
  const unsigned value = std::min(4095U, tenth_kelvin - std::min(tenth_kelvin, kAdditionalSensorOffsetTenthKelvin));
  return static_cast<std::uint16_t>((address & 0xF) << 12 | value);
}

}  // namespace endatsim::protocol::diagnosis

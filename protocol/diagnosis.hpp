// Diagnosis (spec appendix A3, 2.3.5.1, 3.6.3, 3.6.6, 3.9.6, 3.9.7, 3.9.16): the valuation
// numbers' addresses, the temperature scaling and the additional sensors' 115 K offset.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace endatsim::protocol::diagnosis {

// 3.9.6: temperatures are in 0.1 K (word 4 of the EnDat 2.2 area, scaling 000b = 0.1) with
// "0 degC = 273.1 K"; the examples of 3.6.6 (110 degC = 3831) and 3.9.16 (115 degC = 3881) use
// it. The table of 3.9.6 for the additional sensors prints degC with 273.15 K instead (1581 =
// 273.1 K = -0.05 degC); reports here use 273.1 K throughout, a difference of 0.05 degC.
constexpr unsigned kZeroCelsiusTenthKelvin = 2731;
constexpr double celsius(unsigned tenth_kelvin) { return (static_cast<double>(tenth_kelvin) - kZeroCelsiusTenthKelvin) / 10.0; }
constexpr double kelvin(unsigned tenth_kelvin) { return static_cast<double>(tenth_kelvin) / 10.0; }
// Rounded to 0.1 K; negative below 0 K.
long tenth_kelvin_of_celsius(double celsius);
std::string temperature_string(unsigned tenth_kelvin);  // "110.0 degC (383.1 K)"
std::string kelvin_string(unsigned tenth_kelvin);       // "6553.5 K"

// 3.9.6 word 4: bits 0..2 select the scaling factor; only 000b (0.1 K) is defined. Bit 15 is
// the NVM bit. None: another, undefined scaling.
std::optional<double> temperature_scaling(std::uint16_t word4);

// 2.3.5.1 / 3.9.6: "additional sensors" = 4-bit address, 12 bits in 0.1 K with an offset of 115 K.
constexpr unsigned kAdditionalSensorOffsetTenthKelvin = 1150;
constexpr unsigned kAdditionalSensorAddresses = 16;  // a 4-bit address
struct AdditionalSensorValue {
  unsigned address = 0;
  unsigned tenth_kelvin = 0;
};
constexpr AdditionalSensorValue decode_additional_sensor(std::uint16_t data) {
  return {static_cast<unsigned>(data >> 12), (data & 0x0FFFU) + kAdditionalSensorOffsetTenthKelvin};
}
// The 12-bit value for a temperature, clamped to what 12 bits hold (115.0 .. 524.5 K).
std::uint16_t encode_additional_sensor(unsigned address, unsigned tenth_kelvin);

// A3: diagnosis data = 8-bit address | 8-bit value. The address of valuation number n (bit
// n - 1 of operating parameters word 3) is n + 16 k, k = 0..3 ("1 (1+0), 17 (1+16), 33, 49");
// bits 0..5 are valuation numbers 1..6 (3.6.3), bits 5..8 "parameter, states", bits 9..15
// system-specific data. Undefined addresses must be ignored ("if system-specific data are
// transferred the subsequent electronics must ignore undefined addresses").
struct DiagnosisAddress {
  unsigned bit = 0;        // of operating parameters word 3 (and 3.9.7 word 5)
  unsigned area = 0;       // k of n + 16 k
};
// A3's addresses: 1 .. 64, four areas of 16 (n + 16 k, k = 0..3).
constexpr unsigned kDiagnosisAddressMax = 64;
constexpr std::optional<DiagnosisAddress> decode_diagnosis_address(unsigned address) {
  if (address == 0 || address > kDiagnosisAddressMax) return std::nullopt;
  return DiagnosisAddress{(address - 1) % 16, (address - 1) / 16};
}
// The address at which an encoder sends valuation number n (1 .. 6): n, the first area of A3.
constexpr std::uint8_t valuation_number_address(unsigned n) { return static_cast<std::uint8_t>(n); }
constexpr unsigned kValuationNumbers = 6;                // 3.6.3 bits 0 .. 5
constexpr std::uint16_t kValuationNumberBits = 0x003F;
constexpr std::uint16_t kSystemSpecificDataBit = 0x8000;  // 3.6.3 bit 15

}  // namespace endatsim::protocol::diagnosis

// The EnDat 5-bit CRC, spec appendix A4: generator x^5 + x^3 + x + 1, flip-flops preset to 1,
// output inverted, transmitted MSB first.
#pragma once

#include <cstdint>
#include <span>

namespace endatsim::protocol {

// A4.4.1: five flip-flops; the generator x^5 + x^3 + x + 1 without its x^5 term.
inline constexpr unsigned kCrcBits = 5;
inline constexpr std::uint8_t kCrcPolynomial = 0x0B;

// How a CRC generator is set up. The spec's (A4.4.1): flip-flops preset to 1, output inverted.
// Masters in the field got these wrong (docs/model.md §12: preset 0 and no inversion, which two
// devices built from the same wrong settings do not notice).
struct CrcConfig {
  std::uint8_t preset = 0x1F;
  bool final_inversion = true;
  bool operator==(const CrcConfig&) const = default;
};

// CRC over a bit sequence in wire order (each element 0 or 1).
std::uint8_t crc5(std::span<const std::uint8_t> bits);

// MakeCrcNorm (A4.4.2): 8-bit value (address, MRS code, ...) then 16-bit value, both MSB first.
std::uint8_t make_crc_norm(std::uint8_t param8, std::uint16_t param16, const CrcConfig& config = {});

// MakeCrcPos (A4.4.2): F1, [F2 with EnDat 2.2], then `clocks` position bits LSB first.
std::uint8_t make_crc_pos(unsigned clocks, bool error1, bool error2, bool endat22, std::uint64_t position,
                          const CrcConfig& config = {});

}  // namespace endatsim::protocol

#include "endatsim/protocol/crc_parameters.hpp"

#include <array>

namespace endatsim::protocol {
namespace {

using C = CrcConfig;
const std::array kCrcGenerator{
    sim::Parameter<C>{"preset", &C::preset, 0, (1 << kCrcBits) - 1, "A4",
                      "The flip-flops' preset, one bit per CRC bit (the spec's: all set, 1Fh)."},
    sim::Parameter<C>{"final_inversion", &C::final_inversion, 0, 0, "A4",
                      "The CRC is sent (or compared) inverted, as the spec's generator does."},
};

}  // namespace

std::span<const sim::Parameter<CrcConfig>> crc_generator_parameters() { return kCrcGenerator; }

}  // namespace endatsim::protocol

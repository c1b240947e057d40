#pragma once
// The CRC generator's settings as scenario parameter rows (sim/parameter.hpp), shared by the
// encoder's "crc" and the master's "crc": an emulator or a master built with other settings than
// the spec's (appendix A4: flip-flops preset to 1, the result inverted).

#include <span>

#include "endatsim/protocol/crc.hpp"
#include "endatsim/sim/parameter.hpp"

namespace endatsim::protocol {

std::span<const sim::Parameter<CrcConfig>> crc_generator_parameters();

}  // namespace endatsim::protocol

// protocol/ — what both ends of the line agree on, as data: the 14 mode commands
// (mode_command.hpp, spec 2.3), the 5-bit CRC (crc.hpp, appendix A4) and the bit layout of
// the encoder's answer frames (frame.hpp, spec 2.3.1). Master and encoder both use it;
// it depends on nothing else in endatsim.
#pragma once

#include "protocol/crc.hpp"
#include "protocol/frame.hpp"
#include "protocol/mode_command.hpp"

// protocol/ — what both ends of the line agree on, as data: the 14 mode commands
// (mode_command.hpp, spec 2.3), the 5-bit CRC (crc.hpp, appendix A4), the bit layouts of
// the frames (frame.hpp, 2.3.1, 2.3.5, 2.4–2.10), the MRS codes of the memory areas
// (memory_area.hpp, 2.4), the additional-data information codes (additional_data.hpp, 2.3.5),
// the error causes of appendix A2 (error_handling.hpp), the master's bits after its mode bits
// as a receiver takes them (master_bits.hpp, 2.3) and the meaning of the parameter words
// of 3.5, 3.6 and 3.9 (parameters.hpp), the diagnosis values of appendix A3 (diagnosis.hpp), and
// the timing conditions of 2.3.2 with the frame positions they count from (timing.hpp).
// Master, encoder and checker use it; it depends only on sim/time.hpp.
#pragma once

#include "endatsim/protocol/additional_data.hpp"
#include "endatsim/protocol/crc.hpp"
#include "endatsim/protocol/diagnosis.hpp"
#include "endatsim/protocol/error_handling.hpp"
#include "endatsim/protocol/frame.hpp"
#include "endatsim/protocol/master_bits.hpp"
#include "endatsim/protocol/memory_area.hpp"
#include "endatsim/protocol/mode_command.hpp"
#include "endatsim/protocol/parameters.hpp"
#include "endatsim/protocol/timing.hpp"

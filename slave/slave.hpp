// slave/ — the EnDat encoder (D297403 2, 3) as a bit-level state machine that only talks through
// the line's encoder-side signals. It answers all mode commands of 2.3 .. 2.10 (EnDat 2.1 and
// 2.2), with memory areas and write protection, busy, the error handling of appendix A2 and
// additional data.
//   encoder_params.hpp   what an encoder is: EncoderParams, and the model's named choices
//   encoder.hpp          the frame engine on the pins, and the ground truth of each frame
//   frame_bits.hpp       the bits of a frame: the answer sent, the 8 + 16 received, the supplement's start
//   memory.hpp           memory areas, write protection, activation on reset (3)
//   memory_access.hpp    the area selected, Busy, 2.2 accesses, the word being programmed (2.4 .. 2.6)
//   position_source.hpp  positions, multiturn, reference marks, touch probe (2.3.4)
//   additional_data.hpp  additional data 1 and 2 and their rolling values (2.3.5)
//   error_messages.hpp   F1 and F2 and the operating status words 0 and 1 (2.3.1, 3.4.1, 3.4.2)
//   bus_addressing.hpp   the encoder's part in a bus: addressed or not, driver on or off (2.10)
//   parameter_commands.hpp  commands with 8 + 16 bits (2.1 payload, 2.2 supplement): answers, type II, test port
//   readiness.hpp        whether a clock edge is taken: run-up (2.3.3), t_R (2.3.2)
//   data_driver.hpp      the level the encoder sends on DATA and whether its driver is on (2.3)
//   reference.hpp        reference mark schemes (2.3.4.3)
//   eib.hpp              the EIB: its factory image and initial commissioning (3.5.7)
//   profile.hpp          encoder profiles: memory images with their parameters as JSON
#pragma once

#include "endatsim/slave/encoder.hpp"
#include "endatsim/slave/profile.hpp"

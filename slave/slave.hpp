// slave/ — the EnDat encoder as a bit-level state machine that only talks through the line's
// encoder-side signals (encoder.hpp). It answers "Encoder send position values" (2.1, with
// continuous clock) and "Encoder send position values with additional data" (2.2, none
// selected yet); every other mode command is answered as not supported (type I, appendix A2).
// Encoder profiles (profile.hpp): memory images with their parameters as JSON, profiles/*.json.
#pragma once

#include "endatsim/slave/encoder.hpp"
#include "endatsim/slave/profile.hpp"

// Frame diagrams: one frame (or a time window) of a scenario run as an SVG timing diagram —
// CLOCK and DATA at the master's and the encoder's pins, driver enables and the master's
// sampling instants, the frame's fields (mode bits, start bit, F1, F2, position, CRC), the
// timing parameters t_ST, t_cal, t_D and t_m as dimension arrows with the values measured on
// the waveforms, and the checker's violations in red. Long idle stretches are drawn as axis
// breaks. The same scenario and seed give the same bytes.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "endatsim/scenarios/scenario.hpp"

namespace endatsim::scenarios {

struct DiagramOptions {
  std::optional<std::uint64_t> frame;               // index into the run's frames; default: first non-measurement frame
  std::optional<std::pair<Time, Time>> window;      // draw this time window instead of one frame
  std::optional<std::uint64_t> seed;                // overrides the scenario's seed
  Limits limits;                                    // for the run
};

struct Diagram {
  std::string svg;
  std::string caption;  // one line: what was drawn and the measured timing values
};

// Runs the scenario (waveforms through a temporary VCD file) and draws. Throws
// std::invalid_argument when the frame or window does not exist in the run.
Diagram frame_diagram(const Scenario& scenario, const DiagramOptions& options);

}  // namespace endatsim::scenarios

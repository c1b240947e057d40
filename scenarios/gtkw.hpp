#pragma once
// A GTKWave save file (.gtkw) for a run's waveform: it opens on the first frame that is not a
// propagation-delay measurement (the view starts a little before its FE1 and is zoomed to show
// the whole frame; the primary marker sits at FE1), puts a named marker (A, B, ...) at each of
// the first 26 violations, and shows the signals grouped by end, the master's first, with the
// text trace of the decoded frames (RunOptions::vcd_decoded) among the master's.

#include <string>

#include "endatsim/scenarios/runner.hpp"

namespace endatsim::scenarios {

// The save file's text; `vcd_path` is written into it as an absolute path.
std::string gtkw_save_file(const ScenarioResult& result, const std::string& vcd_path);

}  // namespace endatsim::scenarios

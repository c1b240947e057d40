// scenarios/ — JSON scenarios that set up a line, an encoder and a master, script operations
// over time and state expectations (scenario.hpp); the loader with path-precise errors
// (loader.hpp); running one and judging its expectations (runner.hpp); text and JSON
// reports (report.hpp); running one over a grid of its parameters in parallel (sweep.hpp);
// judging a recorded waveform from its wires (capture_check.hpp).
#pragma once

#include "endatsim/scenarios/capture_check.hpp"
#include "endatsim/scenarios/declarations.hpp"
#include "endatsim/scenarios/loader.hpp"
#include "endatsim/scenarios/report.hpp"
#include "endatsim/scenarios/runner.hpp"
#include "endatsim/scenarios/scenario.hpp"
#include "endatsim/scenarios/sweep.hpp"

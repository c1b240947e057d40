// scenarios/ — JSON scenarios that set up a line, an encoder and a master, script operations
// over time and state expectations (scenario.hpp); the loader with path-precise errors
// (loader.hpp); running one and judging its expectations (runner.hpp); text and JSON
// reports (report.hpp); running one over a grid of its parameters in parallel (sweep.hpp);
// judging a recorded waveform from its wires (capture_check.hpp).
#pragma once

#include "scenarios/capture_check.hpp"
#include "scenarios/declarations.hpp"
#include "scenarios/loader.hpp"
#include "scenarios/report.hpp"
#include "scenarios/runner.hpp"
#include "scenarios/scenario.hpp"
#include "scenarios/sweep.hpp"

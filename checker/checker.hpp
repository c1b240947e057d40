// checker/ — timing monitors that observe committed signal changes on the line and the
// master's declared sampling instants, and report every broken timing condition of spec 2.3.2
// with where, when, by how much and which spec row says so (timing_checker.hpp).
#pragma once

#include "endatsim/checker/timing_checker.hpp"

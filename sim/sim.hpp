// sim/ — what the event kernel offers: integer-picosecond time (time.hpp), the kernel with
// deterministic ordering, zero-delay FIFO and cancellable timers (kernel.hpp), 1-bit signals
// with value-change listeners (signal.hpp), transport delays (delay.hpp), and an
// event-driven VCD writer (vcd.hpp), the bounded log a model keeps its frames in
// (record_log.hpp), and a model's parameters as rows (parameter.hpp). It depends on nothing else
// in endatsim.
#pragma once

#include "endatsim/sim/delay.hpp"
#include "endatsim/sim/kernel.hpp"
#include "endatsim/sim/record_log.hpp"
#include "endatsim/sim/signal.hpp"
#include "endatsim/sim/time.hpp"
#include "endatsim/sim/vcd.hpp"

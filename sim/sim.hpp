// sim/ — what the event kernel offers: integer-picosecond time (time.hpp), the kernel with
// deterministic ordering, zero-delay FIFO and cancellable timers (kernel.hpp), 1-bit signals
// with value-change listeners (signal.hpp), transport delays (delay.hpp), and an
// event-driven VCD writer (vcd.hpp). It depends on nothing else in endatsim.
#pragma once

#include "sim/delay.hpp"
#include "sim/kernel.hpp"
#include "sim/signal.hpp"
#include "sim/time.hpp"
#include "sim/vcd.hpp"

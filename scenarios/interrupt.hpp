// Interruption by SIGINT or SIGTERM: the handler only records the signal; runs look at it at
// their next event boundary (and sweeps and capture checks between their steps) and end early,
// their results marked incomplete.
#pragma once

#include <stdexcept>
#include <string>

namespace endatsim::scenarios {

// Installs the handler for SIGINT and SIGTERM; a second signal of either kind ends the process
// at once (the default action), for a run that does not stop.
void install_interrupt_handlers();
// For a library inside another program (the VPI bridge in a simulator): the signal is recorded,
// then the program's own handler, if it had one, is put back and called, so that the simulator
// stops as it always does and endatsim's results say why.
void install_chained_interrupt_handlers();
// The signal that asked to stop, or 0. Safe from any thread.
int interrupt_signal() noexcept;
// As the handler does (tests, and embedders that stop a run from elsewhere); 0 clears it.
void request_interrupt(int signal) noexcept;
// Thrown where a step cannot end early with a partial result (a capture being checked).
class Interrupted : public std::runtime_error {
 public:
  Interrupted(const std::string& what, int signal) : std::runtime_error(what), signal_(signal) {}
  int signal() const { return signal_; }

 private:
  int signal_;
};

// "SIGINT", "SIGTERM" or "signal N".
std::string signal_name(int signal);

}  // namespace endatsim::scenarios

#include "endatsim/scenarios/interrupt.hpp"

#include <atomic>
#include <csignal>

namespace endatsim::scenarios {
namespace {

std::atomic<int> requested{0};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs a lock-free flag");

extern "C" void on_signal(int signal) { requested.store(signal, std::memory_order_relaxed); }

struct sigaction previous_int {}, previous_term {};

extern "C" void on_signal_chained(int signal, siginfo_t* info, void* context) {
  requested.store(signal, std::memory_order_relaxed);
  const struct sigaction& previous = signal == SIGINT ? previous_int : previous_term;
  sigaction(signal, &previous, nullptr);  // the next one goes where it always went
  if ((previous.sa_flags & SA_SIGINFO) != 0) {
    if (previous.sa_sigaction != nullptr) previous.sa_sigaction(signal, info, context);
  } else if (previous.sa_handler != SIG_DFL && previous.sa_handler != SIG_IGN && previous.sa_handler != nullptr) {
    previous.sa_handler(signal);
  }
}

}  // namespace

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  // The next one ends the process. glibc's SA_RESETHAND is 0x80000000, an unsigned constant for
  // the int field: converted on purpose (-fsanitize=implicit-conversion reports it otherwise).
  action.sa_flags = static_cast<int>(SA_RESETHAND);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

void install_chained_interrupt_handlers() {
  struct sigaction action {};
  action.sa_sigaction = on_signal_chained;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_SIGINFO;
  sigaction(SIGINT, &action, &previous_int);
  sigaction(SIGTERM, &action, &previous_term);
}

int interrupt_signal() noexcept { return requested.load(std::memory_order_relaxed); }

void request_interrupt(int signal) noexcept { requested.store(signal, std::memory_order_relaxed); }

std::string signal_name(int signal) {
  if (signal == SIGINT) return "SIGINT";
  if (signal == SIGTERM) return "SIGTERM";
  return "signal " + std::to_string(signal);
}

}  // namespace endatsim::scenarios

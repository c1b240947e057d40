#include "endatsim/sim/signal.hpp"

namespace endatsim::sim {

void Signal::replay_commit(std::uint64_t value) {
  value_ = next_ = value != 0;
  last_change_ = kernel_.now();
  ++changes_;
  notify_value_ = value;
}

}  // namespace endatsim::sim

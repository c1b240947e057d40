#include "endatsim/sim/signal.hpp"

namespace endatsim::sim {

void Signal::write(bool v) {
  // Writing the value it already has, with nothing pending, would commit as no change.
  if (!pending_ && v == value_) return;
  next_ = v;
  if (!pending_) {
    pending_ = true;
    kernel_.request_update(this);
  }
}

bool Signal::commit() {
  pending_ = false;
  if (next_ == value_) return false;
  value_ = next_;
  last_change_ = kernel_.now();
  ++changes_;
  notify_value_ = value_ ? 1 : 0;
  return true;
}

void Signal::replay_commit(std::uint64_t value) {
  value_ = next_ = value != 0;
  last_change_ = kernel_.now();
  ++changes_;
  notify_value_ = value;
}

}  // namespace endatsim::sim

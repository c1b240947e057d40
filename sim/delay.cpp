#include "endatsim/sim/delay.hpp"

namespace endatsim::sim {

void TransportDelay::on_input(std::uint64_t value) {
  const Time delay = value != 0 ? rise_ : fall_;
  if (delay == Time::zero()) {  // the next delta cycle, like any zero-delay wake-up
    kernel_.schedule(Time::zero(), Action{[](void* o, std::uint64_t v) { static_cast<Signal*>(o)->write(v != 0); }, &out_, value});
    return;
  }
  const InFlight change{kernel_.now() + delay, kernel_.take_seq(), value != 0};
  // Equal rise and fall delays keep the changes in order; unequal ones may overtake.
  auto at = in_flight_.end();
  while (at != in_flight_.begin() + static_cast<std::ptrdiff_t>(head_) && change.before(*(at - 1))) --at;
  const bool new_front = at == in_flight_.begin() + static_cast<std::ptrdiff_t>(head_);
  in_flight_.insert(at, change);
  if (new_front) queue_front();
}

void TransportDelay::queue_front() {
  const InFlight& front = in_flight_[head_];
  kernel_.schedule_ordered(front.when, front.seq, Action{&TransportDelay::deliver, this, ++entry_});
}

void TransportDelay::deliver(void* self, std::uint64_t entry) {
  auto* d = static_cast<TransportDelay*>(self);
  if (entry != d->entry_) return;  // an earlier change overtook the one this entry was for
  d->out_.write(d->in_flight_[d->head_].value);
  if (++d->head_ == d->in_flight_.size()) {
    d->in_flight_.clear();
    d->head_ = 0;
    return;
  }
  if (d->head_ >= 64 && 2 * d->head_ >= d->in_flight_.size()) {  // keep the buffer short
    d->in_flight_.erase(d->in_flight_.begin(), d->in_flight_.begin() + static_cast<std::ptrdiff_t>(d->head_));
    d->head_ = 0;
  }
  d->queue_front();
}

}  // namespace endatsim::sim

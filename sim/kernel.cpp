#include "endatsim/sim/kernel.hpp"

#include <algorithm>
#include <stdexcept>

#include "endatsim/sim/signal.hpp"
#include "endatsim/sim/tape.hpp"

namespace endatsim::sim {

Kernel::Kernel() {
  fifo_.resize(256);
  updates_.reserve(64);
  changed_.reserve(64);
}

void Kernel::write_signal(void* signal, std::uint64_t value) { static_cast<Signal*>(signal)->write(value != 0); }

void Kernel::refuse(const char* what) { throw std::logic_error(what); }

void Kernel::schedule_at(Time when, Action action) {
  if (when < now_) throw std::logic_error("Kernel::schedule_at: time in the past");
  schedule(when - now_, action);
}

void Kernel::grow_fifo() {
  std::vector<Action> bigger(fifo_.size() * 2);
  for (std::size_t i = 0; i < fifo_size_; ++i) bigger[i] = fifo_[(fifo_head_ + i) & (fifo_.size() - 1)];
  fifo_.swap(bigger);
  fifo_head_ = 0;
}

void Kernel::run_fifo_snapshot() {
  // Wake-ups added while running belong to the next delta cycle.
  for (std::size_t n = fifo_size_; n > 0 && !stopped_; --n) {
    const Action a = fifo_[fifo_head_];
    fifo_head_ = (fifo_head_ + 1) & (fifo_.size() - 1);  // the ring may have grown in the last a()
    --fifo_size_;
    // A zero-delay delivery written without the indirect call, as in run().
    if (a.fn == &write_signal) static_cast<Signal*>(a.ctx)->write(a.arg != 0);
    else a();
    count_event();
  }
}

void Kernel::commit_updates() {
  // Committing writes nothing: every request of this phase is in updates_ before the
  // listeners, whose writes belong to the next one, run.
  if (tape_ != nullptr) {
    commit_updates_recorded();
    return;
  }
  for (Signal* s : updates_)
    if (s->commit()) changed_.push_back(s);
  updates_.clear();
  for (Signal* s : changed_) s->notify();
  changed_.clear();
}

// commit_updates() while recording: every commit and every monitor's call goes on the tape.
void Kernel::commit_updates_recorded() {
  for (Signal* s : updates_)
    if (s->commit()) {
      changed_.push_back(s);
      tape_->add(TapeItem::Kind::Commit, now_, s, 0, s->committed_value());
    }
  updates_.clear();
  for (Signal* s : changed_) s->notify(*tape_, now_);
  changed_.clear();
}

inline void Kernel::settle() {
  while ((!updates_.empty() || fifo_size_ != 0) && !stopped_) {
    // The common case (one delivery, one pin hop) commits here: no call, no list of changes.
    if (updates_.size() == 1 && tape_ == nullptr) {
      Signal* s = updates_.front();
      updates_.clear();
      if (s->commit()) s->notify();
    } else {
      commit_updates();
    }
    if (fifo_size_ != 0) run_fifo_snapshot();
  }
}

void Kernel::note_step_end() { tape_->add(TapeItem::Kind::StepEnd, now_, nullptr, 0, 0); }

inline void Kernel::end_time_step() {
  if (tape_ != nullptr) [[unlikely]]
    note_step_end();
  for (const Action& a : step_end_) a();
}

void Kernel::replay_step_end() { end_time_step(); }

void Kernel::replay_done(Time last) const {
  if (!updates_.empty() || fifo_size_ != 0) refuse("Kernel::replay_done: work pending after a stretch played");
  if (!queue_.empty() && queue_.top().when <= last) refuse("Kernel::replay_done: an event falls inside the stretch played");
}

void Kernel::run(Time until) {
  stopped_ = false;
  until_ = until;
  if (!updates_.empty() || fifo_size_ != 0) {  // work left at the current time
    settle();
    end_time_step();
  }
  while (!stopped_ && !queue_.empty()) {
    const Time t = queue_.top().when;
    if (t > until) {
      now_ = until;
      break;
    }
    now_ = t;
    do {
      const Action a = queue_.pop().payload;
      if (a.fn == &write_signal) static_cast<Signal*>(a.ctx)->write(a.arg != 0);
      else a();
      count_event();
    } while (!queue_.empty() && queue_.top().when == t && !stopped_);
    settle();
    end_time_step();
  }
}

void Kernel::advance_to(Time t) {
  if (t < now_) throw std::logic_error("Kernel::advance_to: time in the past");
  run(t);
  if (!stopped_) now_ = t;
}

std::optional<Time> Kernel::next_event_time() const {
  if (queue_.empty()) return std::nullopt;
  return queue_.top().when;
}

void Timer::refuse(Time delay) {
  if (delay < Time::zero()) throw std::logic_error("Timer::start: negative delay");
  throw std::logic_error("Timer::start: the expiry would fall after Time::max()");
}

void Timer::start_now() {
  // The next delta cycle, through the kernel's FIFO like any zero-delay wake-up.
  queued_ = true;
  queued_at_ = expiry_;
  kernel_.schedule(Time::zero(), Action{&Timer::fire, this, ++entry_});
}

void Timer::fire(void* self, std::uint64_t entry) {
  auto* t = static_cast<Timer*>(self);
  if (entry != t->entry_) return;  // superseded by an entry for an earlier expiry
  t->queued_ = false;
  if (!t->pending_) return;
  if (t->expiry_ > t->kernel_.now()) {  // restarted since this entry was queued
    t->queue(t->expiry_);
    return;
  }
  t->pending_ = false;
  t->action_();
}

}  // namespace endatsim::sim

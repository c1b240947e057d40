// A 1-bit signal with SystemC semantics: write() takes effect in the next update phase;
// listeners run after the update phase when the committed value changed (writes that cancel
// within one evaluate phase are no change). What listeners write lands in the next delta.
#pragma once

#include <string>
#include <vector>

#include "endatsim/sim/kernel.hpp"
#include "endatsim/sim/tape.hpp"

namespace endatsim::sim {

class SignalBase {
 public:
  virtual ~SignalBase() = default;
  // Update phase, in two passes: every pending value is committed first, then the listeners
  // of the signals that changed run, so no listener sees a half-updated set of signals.
  virtual bool commit() = 0;
  // Listener actions receive the new value as their argument, in place of Action::arg.
  void on_change(Action listener) {
    listeners_.push_back(listener);
    monitors_.push_back(false);
  }
  // A monitor: a listener that only reads (it writes no signal and schedules nothing), so that
  // what it is shown can be recorded and played to it again (tape.hpp).
  void on_change_monitor(Action listener) {
    listeners_.push_back(listener);
    monitors_.push_back(true);
  }
  // The monitor `who` reads this signal's level without listening to it.
  void read_by_monitor(const void* who) { readers_.push_back(who); }
  // A monitor listens to or reads this signal, other than those for which `ignored(its context)`
  // holds: a stretch played from a tape shows it each change.
  template <class Ignored>
  bool observed(Ignored ignored) const {
    for (std::size_t i = 0; i < listeners_.size(); ++i)
      if (monitors_[i] && !ignored(listeners_[i].ctx)) return true;
    for (const void* r : readers_)
      if (!ignored(r)) return true;
    return false;
  }
  bool observed() const {
    return observed([](const void*) { return false; });
  }
  // The object the listener at `place` calls.
  const void* listener_of(std::uint32_t place) const { return listeners_[place].ctx; }
  void notify() const {
    for (const Action& l : listeners_) l.fn(l.ctx, notify_value_);
  }
  // The same while the kernel records: each monitor's call goes on the tape first.
  void notify(Tape& tape, Time now) const {
    for (std::size_t i = 0; i < listeners_.size(); ++i) {
      if (monitors_[i]) tape.add(TapeItem::Kind::Monitor, now, this, static_cast<std::uint32_t>(i), notify_value_);
      listeners_[i].fn(listeners_[i].ctx, notify_value_);
    }
  }
  std::uint64_t committed_value() const { return notify_value_; }
  // Played from a tape: the monitor at `place` is shown `value` again.
  void replay_monitor(std::uint32_t place, std::uint64_t value) const {
    listeners_[place].fn(listeners_[place].ctx, value);
  }
  // Played from a tape: the signal takes `value` now, as if committed (no listener is called).
  virtual void replay_commit(std::uint64_t value) = 0;

 protected:
  std::uint64_t notify_value_ = 0;  // set by commit(), so that notify() needs no virtual call

 private:
  std::vector<Action> listeners_;
  std::vector<bool> monitors_;  // per listener
  std::vector<const void*> readers_;  // monitors that read without listening
};

class Signal final : public SignalBase {
 public:
  Signal(Kernel& kernel, std::string name, bool initial)
      : kernel_(kernel), name_(std::move(name)), value_(initial), next_(initial) {}
  Signal(const Signal&) = delete;
  Signal& operator=(const Signal&) = delete;

  bool read() const { return value_; }
  // Writing the value it already has, with nothing pending, would commit as no change: dropped.
  void write(bool v) {
    if (!pending_ && v == value_) return;
    next_ = v;
    if (!pending_) {
      pending_ = true;
      kernel_.request_update(this);
    }
  }

  const std::string& name() const { return name_; }
  Time last_change() const { return last_change_; }
  std::uint64_t changes() const { return changes_; }

  bool commit() override {
    pending_ = false;
    if (next_ == value_) return false;
    value_ = next_;
    last_change_ = kernel_.now();
    ++changes_;
    notify_value_ = value_ ? 1 : 0;
    return true;
  }
  void replay_commit(std::uint64_t value) override;
  // Played from a tape for a signal no monitor observed: where it stands after the stretch.
  void replay_final(bool value, Time last_change, std::uint64_t changes) {
    value_ = next_ = value;
    notify_value_ = value ? 1 : 0;
    last_change_ = last_change;
    changes_ += changes;
  }

 private:
  Kernel& kernel_;
  std::string name_;
  bool value_;
  bool next_;
  bool pending_ = false;
  Time last_change_{0};
  std::uint64_t changes_ = 0;
};

}  // namespace endatsim::sim

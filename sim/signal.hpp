// A 1-bit signal with SystemC semantics: write() takes effect in the next update phase;
// listeners run after the update phase when the committed value changed (writes that cancel
// within one evaluate phase are no change). What listeners write lands in the next delta.
#pragma once

#include <string>
#include <vector>

#include "sim/kernel.hpp"

namespace endatsim::sim {

class SignalBase {
 public:
  virtual ~SignalBase() = default;
  // Update phase, in two passes: every pending value is committed first, then the listeners
  // of the signals that changed run, so no listener sees a half-updated set of signals.
  virtual bool commit() = 0;
  virtual void notify() = 0;
};

class Signal final : public SignalBase {
 public:
  Signal(Kernel& kernel, std::string name, bool initial)
      : kernel_(kernel), name_(std::move(name)), value_(initial), next_(initial) {}
  Signal(const Signal&) = delete;
  Signal& operator=(const Signal&) = delete;

  bool read() const { return value_; }
  void write(bool v);
  // Listener actions receive the new value (0 or 1) as their argument, in place of Action::arg.
  void on_change(Action listener) { listeners_.push_back(listener); }

  const std::string& name() const { return name_; }
  Time last_change() const { return last_change_; }
  std::uint64_t changes() const { return changes_; }

  bool commit() override;
  void notify() override;

 private:
  Kernel& kernel_;
  std::string name_;
  bool value_;
  bool next_;
  bool pending_ = false;
  Time last_change_{0};
  std::uint64_t changes_ = 0;
  std::vector<Action> listeners_;
};

}  // namespace endatsim::sim

// What the monitors of a stretch of simulated time were shown, in order: every committed change
// of a signal, every call of a monitor (a listener that only reads: the checker, the VCD
// writer), the end of every time step, and what the models told their observers. A stretch
// recorded once can be played to the monitors again later, shifted in time, without running the
// models and the line that made it: the frame-level fast path (docs/performance.md).
#pragma once

#include <cstdint>
#include <vector>

#include "endatsim/sim/time.hpp"

namespace endatsim::sim {

struct TapeItem {
  enum class Kind : std::uint8_t {
    Commit,   // `who` (a SignalBase) took `value`
    Monitor,  // the monitor at place `index` among `who`'s listeners was called with `value`
    StepEnd,  // the time step ended
    Model,    // a model's own item: `who` the model, `index` its kind, `value` its data
  };
  Kind kind = Kind::Commit;
  Time at{0};
  const void* who = nullptr;
  std::uint32_t index = 0;
  std::uint64_t value = 0;
  bool operator==(const TapeItem&) const = default;
};

struct Tape {
  std::vector<TapeItem> items;
  std::uint64_t events = 0;  // kernel events run while recording
  void add(TapeItem::Kind kind, Time at, const void* who, std::uint32_t index, std::uint64_t value) {
    items.push_back(TapeItem{kind, at, who, index, value});
  }
};

}  // namespace endatsim::sim

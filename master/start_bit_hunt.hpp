// The master's search for the encoder's start bit among its samples (D297403 2.3): a true
// fail-safe receiver reads HIGH on the undriven line, so the master waits for a LOW and then
// takes a HIGH as the start bit. HIGH samples before any LOW are counted: too many of them are
// the encoder's type I answer (appendix A2: DATA held HIGH). Without the wait for LOW
// (StartBitDetection::FirstHigh) the first HIGH is the start bit.
#pragma once

#include <cstdint>

namespace endatsim::master {

class StartBitHunt {
 public:
  enum class Result : std::uint8_t { Waiting, StartBit, Type1Error };

  // A new search; `require_low`: wait for a LOW before a HIGH counts.
  void begin(bool require_low) {
    seen_low_ = false;
    require_low_ = require_low;
    high_samples_ = 0;
  }
  // One sample of DATA; `type1_samples`: the HIGH samples before a LOW that make a type I error.
  Result sample(bool value, unsigned type1_samples) {
    if (!seen_low_ && require_low_) {
      seen_low_ = !value;
      return value && ++high_samples_ >= type1_samples ? Result::Type1Error : Result::Waiting;
    }
    return value ? Result::StartBit : Result::Waiting;
  }

 private:
  bool seen_low_ = false;
  bool require_low_ = true;
  unsigned high_samples_ = 0;
};

}  // namespace endatsim::master

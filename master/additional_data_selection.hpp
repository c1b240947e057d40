#pragma once
// master/additional_data_selection.hpp — what the master has selected as additional data 1 and 2
// with "Encoder send position values and selection of memory area" (D297403 2.4.2.2), as far as
// the encoder accepted it; "Encoder receive reset" clears both (2.7). The master expects that
// many additional data in each answer, rolls additional data 1 from it, and selects them again
// after the encoder lost them.

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "endatsim/master/frame_result.hpp"
#include "endatsim/protocol/additional_data.hpp"

namespace endatsim::master {

class AdditionalDataSelection {
 public:
  // A frame the encoder accepted: a selection of additional data, a stop code, or a reset.
  void accepted(const FrameResult& f);
  unsigned count() const {
    return (mrs_[protocol::AdditionalDataNumber::One] ? 1U : 0U) + (mrs_[protocol::AdditionalDataNumber::Two] ? 1U : 0U);
  }
  std::optional<protocol::Information> additional_data_1() const;
  // The MRS codes to select again, additional data 2 first; the selection is empty afterwards.
  std::vector<std::uint8_t> take();

 private:
  protocol::PerAdditionalData<std::optional<std::uint8_t>> mrs_;
};

}  // namespace endatsim::master

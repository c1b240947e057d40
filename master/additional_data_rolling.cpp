#include "endatsim/master/additional_data_rolling.hpp"

#include <algorithm>
#include <bit>

#include "endatsim/protocol/diagnosis.hpp"
#include "endatsim/protocol/parameters.hpp"

namespace endatsim::master {

using I = protocol::Information;

// The temperatures and additional sensors only where word 0 of the 2.2 area says the encoder
// has them (3.9.2); position value 2 in as many words as its width needs (2.3.5.1, words 1 .. 3,
// "always updated by querying the first word").
std::vector<I> AdditionalData1Rolling::schedule(unsigned position_bits) const {
  const DiagnosisReport& report = report_;
  namespace pm = protocol::parameters;
  std::vector<I> diagnosis;
  const DiagnosticsParams& d = diagnostics_;
  if (d.enabled) {
    const std::uint16_t support = report.additional_data_1_support.value_or(pm::kSupportsEveryAdditionalData1);
    const std::uint16_t active = report.configuration.value_or(d.configuration);
    const auto numbers =
        static_cast<unsigned>(std::popcount(static_cast<unsigned>(active & protocol::diagnosis::kValuationNumberBits)));
    diagnosis.insert(diagnosis.end(), std::max(numbers, 1U), I::Diagnosis);
    if (d.temperatures && (support & pm::kSupportsTemperature1) != 0) diagnosis.push_back(I::Temperature1);
    if (d.temperatures && (support & pm::kSupportsTemperature2) != 0) diagnosis.push_back(I::Temperature2);
    if ((support & pm::kSupportsAdditionalSensors) != 0) diagnosis.insert(diagnosis.end(), d.additional_sensors, I::AdditionalSensors);
  }
  std::vector<I> position2;
  if (safety_.position_value_2)
    for (unsigned k = 0; k < protocol::position_value2_words(position_bits); ++k)
      position2.push_back(static_cast<I>(static_cast<unsigned>(I::PositionValue2Word1) + k));
  if (diagnosis.empty() || position2.empty()) return diagnosis.empty() ? position2 : diagnosis;
  std::vector<I> round;
  for (const I item : diagnosis) {
    round.insert(round.end(), position2.begin(), position2.end());
    round.push_back(item);
  }
  return round;
}

std::optional<I> AdditionalData1Rolling::next_additional_data_1(const FunctionContext& ctx, std::optional<I> selected) {
  if (!active()) return std::nullopt;
  const auto round = schedule(ctx.position_bits);
  if (round.empty() || (!selected && !diagnostics_.enabled)) return std::nullopt;
  const std::size_t size = round.size();
  if (slot_ >= size) slot_ = 0;
  if (!selected) {
    slot_ = size - 1;
  } else if (round[slot_] != *selected) {
    // A selection that did not come through (or another one): back to the latest slot that holds
    // what is selected, so that the round goes on rather than starting over.
    std::size_t back = 1;
    while (back <= size && round[(slot_ + size - back) % size] != *selected) ++back;
    if (back > size) return std::nullopt;
    slot_ = (slot_ + size - back) % size;
  }
  slot_ = (slot_ + 1) % size;
  if (selected && round[slot_] == *selected) return std::nullopt;
  return round[slot_];
}

}  // namespace endatsim::master

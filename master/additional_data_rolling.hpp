// Additional data 1 in turn (D297403 2.3.5.1: one information per frame). The diagnosis (one
// interrogation per activated valuation number, A3), the temperatures and the additional sensors,
// and, with the safety comparison, position value 2 before each of them: the master's cyclic reads
// select the next one with "Encoder send position values and selection of memory area"
// (2.4.2.2), and each read still carries what was selected before. A function on top of the
// master's scheduler (master_function.hpp) that reads what the diagnosis setup found.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "endatsim/master/diagnostics.hpp"
#include "endatsim/master/master_function.hpp"
#include "endatsim/master/safety.hpp"
#include "endatsim/protocol/additional_data.hpp"

namespace endatsim::master {

class AdditionalData1Rolling final : public MasterFunction {
 public:
  // `report`: the diagnosis's, whose setup says what the encoder supports and has activated.
  AdditionalData1Rolling(const DiagnosticsParams& diagnostics, const SafetyParams& safety, const DiagnosisReport& report)
      : diagnostics_(diagnostics), safety_(safety), report_(report) {}
  // Whether anything rolls at all.
  bool active() const { return diagnostics_.enabled || safety_.position_value_2; }
  // The round, for what the diagnosis setup has read and the position width.
  std::vector<protocol::Information> schedule(unsigned position_bits) const;
  // What the next cyclic read is to select, or none (it selects nothing); `selected` is what
  // additional data 1 carries now.
  std::optional<protocol::Information> next_additional_data_1(const FunctionContext& ctx,
                                                             std::optional<protocol::Information> selected) override;

 private:
  const DiagnosticsParams& diagnostics_;
  const SafetyParams& safety_;
  const DiagnosisReport& report_;
  std::size_t slot_ = 0;  // where the round stands
};

}  // namespace endatsim::master

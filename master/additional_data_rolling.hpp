// Additional data 1 in turn (D297403 2.3.5.1: one information per frame). The diagnosis (one
// interrogation per activated valuation number, A3), the temperatures and the additional sensors,
// and, with the safety comparison, position value 2 before each of them: the master's cyclic reads
// select the next one with "Encoder send position values and selection of memory area"
// (2.4.2.2), and each read still carries what was selected before.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "endatsim/master/diagnostics.hpp"
#include "endatsim/master/safety.hpp"
#include "endatsim/protocol/additional_data.hpp"

namespace endatsim::master {

class AdditionalData1Rolling {
 public:
  AdditionalData1Rolling(const DiagnosticsParams& diagnostics, const SafetyParams& safety)
      : diagnostics_(diagnostics), safety_(safety) {}
  // Whether anything rolls at all.
  bool active() const { return diagnostics_.enabled || safety_.position_value_2; }
  // The round, for what the diagnosis setup has read (`report`) and the position width.
  std::vector<protocol::Information> schedule(const DiagnosisReport& report, unsigned position_bits) const;
  // What the next cyclic read is to select, or none (it selects nothing); `selected` is what
  // additional data 1 carries now.
  std::optional<protocol::Information> next(const DiagnosisReport& report, unsigned position_bits,
                                            std::optional<protocol::Information> selected);

 private:
  const DiagnosticsParams& diagnostics_;
  const SafetyParams& safety_;
  std::size_t slot_ = 0;  // where the round stands
};

}  // namespace endatsim::master

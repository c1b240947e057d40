// The functions a master runs on top of its scheduler (master_function.hpp) as its MasterParams
// configure them, attached in the order they see each frame: the diagnosis (diagnostics.hpp),
// the safety functions (safety.hpp), additional data 1 in turn (additional_data_rolling.hpp).
// A master without them still reads positions and memory; operations that need them
// (safety_startup, diagnosis_setup) are refused.
#pragma once

#include "endatsim/master/additional_data_rolling.hpp"
#include "endatsim/master/diagnostics.hpp"
#include "endatsim/master/master.hpp"
#include "endatsim/master/safety.hpp"

namespace endatsim::master {

class MasterFunctions {
 public:
  // Attaches to `master`, whose parameters they read: they must outlive its run.
  explicit MasterFunctions(Master& master)
      : diagnosis_(master.params().diagnostics),
        safety_(master.params().safety),
        rolling_(master.params().diagnostics, master.params().safety, diagnosis_.report()) {
    master.add_function(diagnosis_);
    master.add_function(safety_);
    master.add_function(rolling_);
  }
  MasterFunctions(const MasterFunctions&) = delete;
  MasterFunctions& operator=(const MasterFunctions&) = delete;

  const SafetyReport& safety() const { return safety_.report(); }
  const DiagnosisReport& diagnosis() const { return diagnosis_.report(); }

 private:
  Diagnosis diagnosis_;
  SafetyFunctions safety_;
  AdditionalData1Rolling rolling_;
};

}  // namespace endatsim::master

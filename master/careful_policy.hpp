#pragma once
// master/careful_policy.hpp — what a careful master (CarefulMaster) decides when things go wrong:
// repeat a failed frame of a position read, measure t_D again after a change of the transmission
// path, a power interruption or failed frames in a row (D297403 2.1.2), and select the additional
// data again after a power interruption (2.4.2.2). It decides; the master acts on it.

#include <cstdint>

#include "endatsim/master/frame_result.hpp"
#include "endatsim/master/master_params.hpp"

namespace endatsim::master {

class CarefulPolicy {
 public:
  CarefulPolicy(const CarefulMaster& params, bool delay_compensation);

  // What the installation tells the master.
  void line_changed();
  void power_interrupted(bool additional_data_selected);
  // Each finished frame: failed frames in a row call for a new delay measurement.
  void frame_done(const FrameResult& f);
  // A position read starts with its full number of retries.
  void position_read_started() { retries_left_ = params_.retries; }
  // Whether to repeat this frame (a failed frame of a position read, while retries are left);
  // any other frame gives the retries back.
  bool retry(const FrameResult& f, bool position_read);

  struct Interruption {
    bool remeasure = false;  // measure t_D again first
    bool reselect = false;   // select the additional data again
  };
  bool interruption_due() const { return remeasure_due_ || reselect_due_; }
  // What is due before the next frame; nothing is due afterwards.
  Interruption take_interruption();

  std::uint64_t retries() const { return retries_done_; }
  std::uint64_t remeasurements() const { return remeasurements_; }

 private:
  CarefulMaster params_;
  bool delay_compensation_;
  unsigned retries_left_ = 0;
  std::uint64_t retries_done_ = 0;
  unsigned failures_in_a_row_ = 0;
  bool remeasure_due_ = false;
  bool reselect_due_ = false;
  std::uint64_t remeasurements_ = 0;
};

}  // namespace endatsim::master

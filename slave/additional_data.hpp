// The encoder's additional data (D297403 2.3.5, 2.4.2.2): which information additional data 1
// and 2 carry, the type III and IV answers of appendix A2, the acknowledgments (I = 5 .. 8), the
// values that roll from one interrogation to the next (diagnosis, A3; additional sensors) and the
// status byte. It reads the encoder's memory, sensors and position source; the frame engine
// decides when a datum is sent.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "endatsim/protocol/protocol.hpp"
#include "endatsim/slave/encoder_params.hpp"
#include "endatsim/slave/memory.hpp"
#include "endatsim/slave/position_source.hpp"

namespace endatsim::slave {

class AdditionalData {
 public:
  // The three belong to the encoder and outlive this part.
  AdditionalData(const EncoderParams& params, const Memory& memory, const PositionSource& positions);

  // What additional data 1 or 2 carries; none: not selected.
  std::optional<Information> selected(protocol::AdditionalDataNumber which) const { return selection_[which]; }
  // The data selected are the same in every frame and sending them changes nothing here (no
  // rolling address, no latched or timed value): the frame-level fast path (docs/performance.md).
  bool frame_invariant() const;
  // 2.4.2.2: an MRS code 40h .. 5Fh selects an information or stops additional data 1 or 2.
  void select(std::uint8_t mrs);
  // I = 7: the MRS code and block address as acknowledged (inverted after an error, A2 type II).
  void acknowledge_mrs(std::uint8_t mrs, std::uint8_t block);
  // I = 5 / 6 (2.5.1, 2.6.1): the address and parameter of the last memory access, as acknowledged.
  void acknowledge_memory_access(std::uint8_t address, std::uint16_t value);
  // 2.8.1: the port address of the last 2.2 test command (I = 8; test values, I = 9 .. 11).
  void set_test_port(std::uint8_t port) { test_port_ = port; }
  std::uint8_t test_port() const { return test_port_; }
  // 2.4.2.3: the block address of the asynchronous position's memory area, "time delay k".
  void set_asynchronous_time_delay(std::uint8_t k) { asynchronous_time_delay_ = k; }
  // "Encoder receive reset" or power-on (2.4.2.2, 2.7): nothing selected, test port 0, the
  // rolling values from their start.
  void restart();

  // Appends the selected data to `answer` (docs/model.md §2: additional data 2 before additional
  // data 1) and their status bytes to the frame's record. `busy` is the Busy bit (2.3.1).
  void append(std::vector<std::uint8_t>& answer, std::vector<std::uint8_t>& statuses, Time frame_start,
              std::uint64_t true_position, bool busy);

 private:
  void append_datum(std::vector<std::uint8_t>& answer, std::vector<std::uint8_t>& statuses, protocol::AdditionalDataNumber which,
                    Time frame_start, std::uint64_t true_position, bool busy);
  std::optional<protocol::ErrorCause> type3_cause(Information i, protocol::AdditionalDataNumber which) const;
  bool answers_nop(Information i) const;
  std::uint8_t status_byte(Information i, bool busy) const;
  std::uint16_t content(Information i, Time frame_start, std::uint64_t true_position);
  std::uint16_t position_value2(Time frame_start, std::uint64_t true_position);
  std::uint16_t next_diagnosis_value();
  bool diagnosis_activated() const;

  const EncoderParams& params_;
  const Memory& memory_;
  const PositionSource& positions_;
  protocol::PerAdditionalData<std::optional<Information>> selection_;
  protocol::PerAdditionalData<std::optional<protocol::ErrorCause>> type3_;  // A2: answered with I = 15 / 31 until reselected
  std::uint8_t mrs_ = 0, block_ = 0;              // I = 7
  std::uint8_t test_port_ = 0;                    // I = 8; forced dynamic sampling (3.5.3)
  std::uint8_t memory_address_ = 0;               // I = 5 / 6
  std::uint16_t memory_value_ = 0;
  std::uint8_t asynchronous_time_delay_ = 0;      // 2.4.2.3: 0 after switch-on or reset
  // 2.3.5.1: "position value 2 or test values are always updated by querying the first word".
  std::uint64_t position2_latched_ = 0;
  std::uint64_t test_value_latched_ = 0;
  std::uint64_t asynchronous_latched_ = 0;
  std::size_t diagnosis_index_ = 0;
  unsigned sensor_address_ = 0;
};

}  // namespace endatsim::slave

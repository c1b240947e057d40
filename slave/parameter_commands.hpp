// The encoder's part in the mode commands that carry 8 + 16 bits: after the mode bits (EnDat 2.1,
// D297403 2.4 .. 2.10) or as the command supplement after the position (EnDat 2.2, 2.4.2 .. 2.8.1).
// What it decides on their address (MRS code, port) and parameter: the acknowledgment, an A2
// type II error, the memory operation and its access time, a selection of additional data; and
// what outlives a frame for them (the test port of 2.8, a transmission left incomplete, A2
// cause 3). The frame engine (encoder.hpp) receives the bits and sends the answers.
#pragma once

#include <cstdint>
#include <optional>

#include "endatsim/protocol/protocol.hpp"
#include "endatsim/slave/additional_data.hpp"
#include "endatsim/slave/bus_addressing.hpp"
#include "endatsim/slave/eib.hpp"
#include "endatsim/slave/encoder_params.hpp"
#include "endatsim/slave/memory.hpp"
#include "endatsim/slave/memory_access.hpp"

namespace endatsim::slave {

class ParameterCommands {
 public:
  // A memory operation decided during a frame and carried out when it completes.
  struct Pending {
    enum class Kind : std::uint8_t { None, Select, Write, Reset } kind = Kind::None;
    Selection selection;
    std::uint8_t address = 0;
    std::uint16_t value = 0;
  };
  // The answer to one command.
  struct Decision {
    std::optional<protocol::ErrorCause> error;  // A2 type II: address and parameter inverted
    std::uint8_t address = 0;                   // as acknowledged (inverted after an error)
    std::uint16_t parameter = 0;
    Time start_delay{0};  // t_ac, when the start bit waits for it (MemoryAccessPlacement::InFrame)
    bool silent = false;  // 2.10: a communication command for another encoder; no answer
  };

  // Every part belongs to the encoder and outlives this one.
  ParameterCommands(const EncoderParams& params, Memory& memory, MemoryAccess& access, AdditionalData& additional_data,
                    const EibCommissioning& eib, BusAddressing& bus);

  // The command's 8 + 16 bits are in at `now`: decide, begin an NVM write, note the busy time.
  Decision decide(protocol::ModeCommand command, std::uint32_t payload, Time now);
  // A 2.2 command supplement received (2.4.2 .. 2.8.1): the error it causes, if any; `ignored`
  // when a memory access meets Busy (2.3.1 note 1: "ignored" with 2.2 commands).
  struct SupplementDecision {
    bool memory_access = false;  // a selection, read or write: `error` is the frame's verdict
    std::optional<protocol::ErrorCause> error;
    bool ignored = false;
  };
  SupplementDecision decide_supplement(protocol::ModeCommand command, std::uint32_t supplement);
  // 2.4.2.1: more clock pulses than necessary after a 2.2 selection of a memory area: A2 cause 2,
  // the MRS code and block address acknowledged inverted, the selection not made.
  void selection_disrupted(std::uint32_t supplement);
  // The frame's operation, handed over once (none after an error or a new frame).
  Pending take_pending();
  void forget_pending() { pending_ = {}; }
  // A parameter frame ended before its 8 + 16 bits were in: the next acknowledgment carries
  // A2 cause 3.
  void transmission_cut_short() { transmission_incomplete_ = true; }
  // 2.8: the port "Encoder send test values" reads; 0 after a reset or power-on.
  std::uint8_t test_port() const { return test_port_; }
  void restart() { test_port_ = 0; }

 private:
  std::optional<protocol::ErrorCause> carry_out(protocol::ModeCommand command, std::uint8_t address,
                                                std::uint16_t parameter, std::uint16_t& echo, Time& t_ac, bool& silent);

  const EncoderParams& params_;
  Memory& memory_;
  MemoryAccess& access_;
  AdditionalData& additional_data_;
  const EibCommissioning& eib_;
  BusAddressing& bus_;
  Pending pending_;
  std::uint8_t test_port_ = 0;
  bool transmission_incomplete_ = false;
};

}  // namespace endatsim::slave

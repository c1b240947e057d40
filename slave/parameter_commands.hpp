// The encoder's part in the EnDat 2.1 mode commands that carry 8 + 16 bits after the mode bits
// (D297403 2.4 .. 2.10): what it decides on their address and parameter (the acknowledgment, an
// A2 type II error, the memory operation carried out when the frame completes, the access time)
// and what outlives a frame for them (the test port of 2.8, a transmission left incomplete, A2
// cause 3). The frame engine (encoder.hpp) receives the bits and sends the answer.
#pragma once

#include <cstdint>
#include <optional>

#include "endatsim/protocol/protocol.hpp"
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
  ParameterCommands(const EncoderParams& params, Memory& memory, MemoryAccess& access, const EibCommissioning& eib,
                    BusAddressing& bus);

  // The command's 8 + 16 bits are in at `now`: decide, begin an NVM write, note the busy time.
  Decision decide(protocol::ModeCommand command, std::uint32_t payload, Time now);
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
  const EibCommissioning& eib_;
  BusAddressing& bus_;
  Pending pending_;
  std::uint8_t test_port_ = 0;
  bool transmission_incomplete_ = false;
};

}  // namespace endatsim::slave

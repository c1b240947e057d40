// What the master is asked to do (Operation): a script's steps and the frames the master
// expands them into, each with the purpose its frames serve (the start-up routine, the checksum
// check, a safety or diagnosis read). The parts that watch the frames judge them by that purpose.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <utility>
#include <vector>

#include "endatsim/protocol/protocol.hpp"
#include "endatsim/sim/time.hpp"

namespace endatsim::master {

using protocol::ModeCommand;
using sim::Time;

struct Operation {
  // ReadPosition sends `command` (any mode command, with `address`/`parameter` as the 2.1
  // payload or the 2.2 supplement); AwaitNotBusy sends "Encoder send position values with
  // additional data" until additional data 1 shows Busy = 0 (2.5.1, 2.6.1), at most `count` times.
  // PowerOnSequence drives CLOCK as 2.3.3 asks after switching on; StartupRoutine is the German
  // brochure's (older edition) switch-on routine with EnDat 2.1 commands only (reset, wait 50 ms, read and clear
  // alarms and warnings, read words 13 and 37; docs/model.md §8).
  // VerifyChecksum reads the encoder manufacturer's words 4 .. 47 with 2.1 frames and compares
  // word 47 with their sum (3.5.26).
  // SafetyStartup runs the switched-on safety checks before the axis is released (safety.hpp):
  // CrcSelfTest (no frames), the checksums, forced dynamic sampling and StartupPositions, which
  // reads `command` until the position values agree. ReadEndat22Area reads the words of the 2.2
  // area in `endat22_words` through additional data 1.
  // DiagnosisSetup reads what the diagnosis needs; DiagnosisActivate then writes word 3 of the
  // operating parameters and resets the encoder if it differs (diagnostics.hpp).
  enum class Kind : std::uint8_t {
    MeasureDelay, ReadPosition, Wait, AwaitNotBusy, PowerOnSequence, StartupRoutine, VerifyChecksum,
    SafetyStartup, CrcSelfTest, ReadEndat22Area, StartupPositions, DiagnosisSetup, DiagnosisActivate
  };
  // What a frame of the start-up routine, the checksum check or a safety check is for.
  enum class Purpose : std::uint8_t {
    None, Step, Errors, Warnings, Word13, Word37, ChecksumWord,
    ErrorSources, Endat22Lsb, Endat22Msb, ForcedTest, ForcedError1, ForcedError2, ForcedOff, DiagnosisWarnings,
    DiagnosisConfiguration, CommandSet
  };
  Kind kind = Kind::ReadPosition;
  std::optional<Time> at;  // absolute start; otherwise when the previous operation has finished
  ModeCommand command = ModeCommand::EncoderSendPositionValues;
  std::optional<std::uint8_t> mode_bits;  // send these six bits instead (a disturbed mode command)
  unsigned count = 1;
  Time cycle{0};
  Time duration{0};
  // 2.3.1: with "Encoder send position values" the clock may run on through further words
  // (continuous clock); this many words follow the first one in each frame.
  unsigned continuous_words = 0;
  std::uint8_t address = 0;     // address, MRS code or port address
  std::uint16_t parameter = 0;  // parameter, instruction or block address (low byte)
  int clock_adjust = 0;         // clock pulses more (+) or fewer (-) than the frame needs (a fault)
  Purpose purpose = Purpose::None;
  unsigned manufacturer_word = 0;  // Purpose::ChecksumWord: which of words 4 .. 47; Endat22*: of 0 .. 63
  std::uint64_t endat22_words = ~std::uint64_t{0};  // ReadEndat22Area: bit w = word w
  std::size_t script_index = 0;  // set by enqueue(); the frames' FrameResult::operation
  // Part of a sequence the master expanded (a memory read, a setup): the reads of words 0 and 1
  // after an error message or WRN wait until it is over, lest their memory area selection
  // (2.4.1) come between its selection and its reads.
  bool expanded = false;
};

// The operations the master expands from one script operation (a routine, a memory read, a
// setup): they share its script index and run before what is queued.
struct Sequence {
  std::size_t script_index = 0;
  std::vector<Operation> ops;
  Operation& frame(ModeCommand c, std::uint8_t address = 0, std::uint16_t parameter = 0,
                   Operation::Purpose purpose = Operation::Purpose::None, unsigned word = 0) {
    Operation& o = ops.emplace_back();
    o.script_index = script_index;
    o.command = c;
    o.address = address;
    o.parameter = parameter;
    o.purpose = purpose;
    o.manufacturer_word = word;
    return o;
  }
  Operation& add(Operation::Kind k) {
    Operation& o = ops.emplace_back();
    o.kind = k;
    o.script_index = script_index;
    return o;
  }
};

// The operations still to run, in order: the script's, and in front of them what the master puts
// there (a sequence an operation expands into, reads of words 0 and 1, a new measurement).
class OperationQueue {
 public:
  // One of the script's operations, numbered in the order they came.
  void enqueue(Operation op) {
    op.script_index = enqueued_++;
    ops_.push_back(std::move(op));
  }
  void push_front(Operation op) { ops_.push_front(std::move(op)); }
  // A sequence's operations, in their order, before the rest.
  void insert_front(const std::vector<Operation>& ops) { ops_.insert(ops_.begin(), ops.begin(), ops.end()); }
  bool empty() const { return ops_.empty(); }
  Operation take() {
    Operation o = std::move(ops_.front());
    ops_.pop_front();
    return o;
  }

 private:
  std::deque<Operation> ops_;
  std::size_t enqueued_ = 0;
};

}  // namespace endatsim::master

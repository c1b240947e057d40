// A function of the subsequent electronics that runs on top of the master's operation scheduler:
// the safety functions (safety.hpp), the diagnosis (diagnostics.hpp), additional data 1 in turn
// (additional_data_rolling.hpp). The scheduler knows such a function only through this
// interface: it offers it the operations it does not plan itself, hands it every frame as it
// ends, asks it which word of the operating status (3.4.1, 3.4.2) is to be read next and what
// the next cyclic read is to select. functions.hpp builds the set a configured master runs.
#pragma once

#include <cstdint>
#include <optional>

#include "endatsim/master/frame_result.hpp"
#include "endatsim/master/operation.hpp"
#include "endatsim/protocol/additional_data.hpp"

namespace endatsim::master {

class ParameterBook;
class ChecksumVerification;
struct MasterParams;

// What a function may read of the master when it plans or judges.
struct FunctionContext {
  const Operation& operation;            // the operation being planned, or the frame's
  const MasterParams& params;
  const ParameterBook& book;             // the encoder's memory as read (2.4 .. 2.6)
  const ChecksumVerification& checksum;  // words 4 .. 47 as VerifyChecksum read them (3.5.26)
  unsigned position_bits;                // what the master clocks for the position value
  Time now;
};

// What became of an operation offered to a function.
struct Planned {
  enum class What : std::uint8_t {
    NotMine,   // another function's, or nobody's
    Expanded,  // the function put its frames into the sequence (it may have put none)
    Done,      // carried out at once, without frames
    Frames,    // the operation's own command, sent up to `frames` times (ends_operation may end it sooner)
  };
  What what = What::NotMine;
  unsigned frames = 0;
};

// A read of a word of the operating status (MRS B9) a function asks for.
struct StatusRead {
  std::uint8_t address = 0;  // 0: error sources (3.4.1), 1: warnings (3.4.2)
  Operation::Purpose purpose = Operation::Purpose::None;
};

class MasterFunction {
 public:
  virtual ~MasterFunction() = default;

  // An operation the scheduler does not plan itself (ctx.operation); `plan` carries its script
  // index for the frames it expands into.
  virtual Planned plan(const FunctionContext& ctx, Sequence& plan) {
    (void)ctx, (void)plan;
    return {};
  }
  // The whole EnDat 2.2 area (words 0 .. 63, 3.9) has been read: `complete` when word 63 came
  // in, false when the encoder has no such area (word 37, 3.5.22) and nothing was read.
  virtual void endat22_area_read(const FunctionContext& ctx, bool complete) { (void)ctx, (void)complete; }
  // A frame of `ctx.operation` ended (not a delay measurement's). f.error_detected, what the
  // master made of the error messages, may be refined.
  virtual void on_frame(FrameResult& f, const FunctionContext& ctx) { (void)f, (void)ctx; }
  // Whether `f` ends its operation before its count is reached (`last`: it was the last anyway).
  virtual bool ends_operation(const FrameResult& f, const FunctionContext& ctx, bool last) {
    (void)f, (void)ctx, (void)last;
    return false;
  }
  // A word of the operating status that is to be read before the next frame; the scheduler
  // calls status_read_planned() once it has queued the read.
  virtual std::optional<StatusRead> status_read_due() const { return std::nullopt; }
  virtual void status_read_planned() {}
  // What a cyclic read with additional data is to select with "Encoder send position values
  // and selection of memory area" (2.4.2.2), given what additional data 1 carries now; none:
  // it stays as it is.
  virtual std::optional<protocol::Information> next_additional_data_1(const FunctionContext& ctx,
                                                                     std::optional<protocol::Information> selected) {
    (void)ctx, (void)selected;
    return std::nullopt;
  }
};

}  // namespace endatsim::master

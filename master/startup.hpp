// The routines that read the encoder's memory: with EnDat 2.1 frames, each with what it found, the
// German brochure's (older edition) start-up routine (StartupRoutine, docs/model.md §8) and the
// check of the encoder manufacturer's checksum (ChecksumVerification, D297403 3.5.26); with
// EnDat 2.2 frames, the words of the EnDat 2.2 area (plan_endat22_read, 2.5.1). The master
// expands them into frames (plan) and hands each frame of theirs back (note).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "endatsim/master/frame_result.hpp"
#include "endatsim/master/operation.hpp"

namespace endatsim::master {

// What the start-up routine found.
struct StartupInfo {
  bool completed = false;  // every frame of the routine answered without error
  std::optional<std::uint16_t> errors;    // operating status word 0, before clearing (3.4.1)
  std::optional<std::uint16_t> warnings;  // word 1 (3.4.2)
  std::optional<std::uint16_t> word13;    // clock pulses for the position value (3.5.6)
  std::optional<std::uint16_t> word37;    // EnDat command set (3.5.22)
  unsigned failed_frames = 0;
};

class StartupRoutine {
 public:
  // Reset, 50 ms, alarms and warnings read, 0000h written to words 0 and 1, reset, 50 ms (3.4.1),
  // words 13 and 37; with delay compensation the measurement after them (2.1.2).
  void plan(Sequence& s, bool measure_delay);
  static bool of_routine(Operation::Purpose p);
  // A frame of the routine; the position width word 13 gave, when it gave one.
  std::optional<unsigned> note(Operation::Purpose p, const FrameResult& f);
  const StartupInfo& info() const { return info_; }

 private:
  StartupInfo info_;
};

// What VerifyChecksum found (3.5.26).
struct ChecksumCheck {
  bool complete = false;  // every word was read
  std::uint16_t stored = 0;    // word 47
  std::uint16_t computed = 0;  // word 4 + ... + word 46, overflow ignored
  bool ok() const { return complete && stored == computed; }
};

class ChecksumVerification {
 public:
  // Words 4 .. 47 of the areas A1 (addresses 4 .. 15), A3 and A5 (addresses 0 .. 15 each).
  void plan(Sequence& s);
  void note(const Operation& o, const FrameResult& f);
  const std::optional<ChecksumCheck>& result() const { return result_; }
  const std::vector<std::uint16_t>& words() const { return words_; }  // 48, as read

 private:
  std::optional<ChecksumCheck> result_;
  std::vector<std::uint16_t> words_;
  unsigned read_ = 0;
};

// 2.5.1: the words of the EnDat 2.2 area (MRS BD, selectable only with 2.2 mode commands) whose
// bits `words` sets (bit w: word w), each selected with its address and read back in additional
// data 1 as address | LSB (I = 5) and address | MSB (I = 6) once Busy is reset. False, and
// nothing planned, when word 37 (`word37`, read just before) lacks the 2.2 command set: such an
// encoder has no 2.2 area.
bool plan_endat22_read(Sequence& s, std::uint64_t words, std::optional<std::uint16_t> word37);

}  // namespace endatsim::master

// capture/ — waveforms recorded elsewhere, read as a stream of level changes of named 1-bit
// signals: VCD from any HDL simulator (vcd.cpp), sigrok session files as PulseView and
// sigrok-cli save them (sigrok.cpp), CSV from logic analyzers (csv.cpp). The checker's
// `endatsim check` reads captures through this interface only; nothing here knows EnDat.
//
// Readers stream: memory does not grow with the length of a capture. Bad input throws
// CaptureError with the file, the line (or the entry inside a zip) and what was expected.
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "endatsim/sim/time.hpp"

namespace endatsim::capture {

using sim::Time;

// `text` with every byte that is not printable ASCII or part of a valid UTF-8 character shown as
// \xNN: a message that quotes a file's bytes stays one readable line of valid UTF-8 (JSON and
// XML reports carry it).
std::string printable(std::string_view text);
// The length of the valid UTF-8 character of two to four bytes at `text[i]` (no overlong forms,
// no surrogates), or 0.
std::size_t utf8_length(std::string_view text, std::size_t i);

// The message is made printable: it quotes bytes of a file that may be anything.
class CaptureError : public std::runtime_error {
 public:
  explicit CaptureError(const std::string& what) : std::runtime_error(printable(what)) {}
};

// A change of one signal's level. Values are '0', '1' or 'x' (unknown, undriven, conflicting:
// VCD x/z/U/X/Z/W/-, and H/L read as 1/0 because they are weak drives of those levels).
struct Change {
  Time time{0};
  std::uint32_t signal = 0;  // index into Reader::signals()
  char value = 'x';
};

class Reader {
 public:
  virtual ~Reader() = default;
  // Full names of the 1-bit signals the capture holds, in a fixed order ("top.dut.clock",
  // "clock[3]" for a bit of a vector, a sigrok channel name, a CSV column header).
  virtual const std::vector<std::string>& signals() const = 0;
  // Further names of signals, each with the index of the signal it names: a VCD identifier
  // declared under several scopes (Icarus, Verilator and VCS do this for a port and the net it
  // connects). Any of a signal's names selects it.
  virtual const std::vector<std::pair<std::string, std::uint32_t>>& aliases() const {
    static const std::vector<std::pair<std::string, std::uint32_t>> kNone;
    return kNone;
  }
  // The capture's time resolution: a VCD's timescale, a logic analyzer's sample period. A
  // timing limit closer than this to a measured value cannot be decided from the capture.
  virtual Time resolution() const = 0;
  // True for a logic analyzer's samples (an edge happened up to one resolution before it shows);
  // false for a simulator's event times, which are exact at the timescale.
  virtual bool sampled() const = 0;
  // How far an edge's time as read may be from the file's: a logic analyzer's sample period, a
  // picosecond for a VCD whose timescale is finer than the picosecond (its times are rounded),
  // none for exact times.
  virtual Time uncertainty() const { return sampled() ? resolution() : Time::zero(); }
  // The file's own timescale as written ("1 fs"), for a format that has one.
  virtual std::string timescale() const { return {}; }
  // Only the signals with these indices are reported by next() (default: all). Readers may
  // skip work for the others.
  virtual void select(const std::vector<std::uint32_t>& wanted) = 0;
  // The next change in time order (changes at equal times in file order); false at the end.
  // Every selected signal's initial level is reported as a change at the capture's start.
  virtual bool next(Change& change) = 0;
  // The capture's last instant once next() has returned false: a VCD's last timestamp, a logic
  // analyzer's last sample or row, which may lie after the last change. A frame the capture's
  // end cuts is told from one that ended by how long CLOCK was HIGH before it.
  virtual Time end() const = 0;
  // The file as named by the user, for messages.
  virtual const std::string& path() const = 0;
  // Bytes read so far and the file's size, for progress on long captures.
  virtual std::uint64_t bytes_read() const = 0;
  virtual std::uint64_t bytes_total() const = 0;
};

// Opens a capture by its content (a VCD header, a zip signature) and, for CSV, its extension
// (.csv). Throws CaptureError naming the file when it cannot be read or is of no known format.
std::unique_ptr<Reader> open(const std::string& path);

// Whether the file begins like a zip archive (a sigrok session): its first local header's "PK\3\4".
bool starts_like_zip(const std::string& path);

// Readers of each format (open() picks one of them).
std::unique_ptr<Reader> open_vcd(const std::string& path);
std::unique_ptr<Reader> open_sigrok(const std::string& path);
std::unique_ptr<Reader> open_csv(const std::string& path);

// The index of the signal the user means by `name`: one of its full names (aliases included), or
// a suffix of one that ends at a scope separator ('.', '/', ':') and matches one signal only.
// Throws CaptureError listing the candidates, aliases among them, when none or several match.
std::uint32_t find_signal(const Reader& reader, const std::string& name);

}  // namespace endatsim::capture

// Event-driven VCD writer: records signals as they change and writes the committed values
// once at the end of each time step. 1-bit wires, short identifiers, no $comment after
// $enddefinitions (sigrok reads nothing otherwise), buffered output, no wall-clock date
// so that the same run gives the same bytes. Written to a part file beside the path and renamed
// into place by finish(), so that no half-written VCD ever carries the name; every write and the
// close are checked (finish() throws, naming the path), and the destructor never throws: without
// finish() the part file goes. "-" writes to standard output.
#pragma once

#include <array>
#include <cstdio>
#include <cstring>
#include <deque>
#include <string>
#include <unordered_map>
#include <vector>

#include "endatsim/sim/signal.hpp"

namespace endatsim::sim {

class VcdWriter {
 public:
  VcdWriter(Kernel& kernel, const std::string& path);
  ~VcdWriter();
  VcdWriter(const VcdWriter&) = delete;
  VcdWriter& operator=(const VcdWriter&) = delete;

  // Register before start(); `scope` groups wires in viewers (e.g. "master", "encoder").
  void add(Signal& signal, const std::string& scope, const std::string& name);
  // A text trace: a VCD "string" variable, GTKWave's extension (sigrok skips its values).
  // Register before start(); the handle is for set_text().
  std::size_t add_text(const std::string& scope, const std::string& name);
  // The text the trace shows from now on; each run of spaces becomes one '_' (a VCD value is one token).
  void set_text(std::size_t handle, const std::string& text);
  void start();
  void finish();

  // The frame-level fast path (docs/performance.md). What this writer writes for a stretch of a
  // tape is prepared once and written again each time the stretch is played: a time step's value
  // lines are the same bytes, only its time stamp moves. The writer reads no signal for it.
  struct Stretch {
    struct Step {
      Time at;                           // from the stretch's origin
      std::uint32_t begin = 0, end = 0;  // its value lines in `lines`
    };
    std::vector<Step> steps;  // one per end of a time step on the tape, in order
    std::string lines;
    std::size_t covered = 0;  // the tape's items up to the last end of a time step
    std::vector<std::pair<std::size_t, bool>> written;  // each probe with a line: its last value
  };
  // The tape starts with nothing of this writer's waiting for the end of a time step (quiet());
  // the steps' times are kept from `origin`.
  Stretch prepare(const Tape& tape, Time origin) const;
  // A listener of this writer's: its calls on a tape are in a Stretch.
  bool is_probe(const void* listener) const { return probe_of_.count(listener) != 0; }
  bool quiet() const { return dirty_.empty(); }
  // In place of the ends of the time steps [first, last) of `stretch`, played from `origin` on
  // (a text set before them is written in the first, as at the end of any time step).
  void play_steps(const Stretch& stretch, std::size_t first, std::size_t last, Time origin);
  // After the stretch's last step: the values written stand as they did after the recording.
  void play_end(const Stretch& stretch);

 private:
  struct Probe {
    VcdWriter* owner;
    std::size_t index;
    Signal* signal;
    std::string scope;
    std::string name;
    std::string id;
    bool written;
    bool dirty;
    // The value's line, "0<id>\n", with the value at [0]: written with one copy per change.
    std::array<char, 8> line{};
    std::size_t line_size = 0;
  };
  static void on_change(void* probe, std::uint64_t value);
  static void on_step_end(void* self, std::uint64_t);
  // The texts set in this time step, with the time stamp if there is none for it yet.
  void write_texts(Time now);
  void stamp_once(Time now);  // the time stamp for `now`, unless it was written
  void stamp(Time t);  // "#<t>" and a new line
  void flush_if_full();
  // Room for `n` more bytes at the end of the buffer (written out first when it is full).
  char* room(std::size_t n) {
    if (used_ + n > buffer_.size()) make_room(n);
    return buffer_.data() + used_;
  }
  void make_room(std::size_t n);
  void append(const char* text, std::size_t n) {
    std::memcpy(room(n), text, n);
    used_ += n;
  }
  void append(const std::string& text) { append(text.data(), text.size()); }
  static constexpr std::size_t kBufferSize = std::size_t{1} << 20;
  void write_buffer();

  Kernel& kernel_;
  std::FILE* file_;
  std::string path_;
  std::string part_;
  struct TextProbe {
    std::string scope;
    std::string name;
    std::string id;
    std::string pending;
    bool dirty = false;
  };
  std::deque<Probe> probes_;  // stable addresses: each is its signal's listener context
  std::unordered_map<const void*, std::size_t> probe_of_;  // by listener context
  std::vector<TextProbe> texts_;
  bool texts_dirty_ = false;
  std::vector<Probe*> dirty_;  // in the order of their first change in this time step
  std::string buffer_;    // kBufferSize bytes, of which the first used_ are to be written
  std::size_t used_ = 0;
  Time stamped_{-1};  // the last "#time" written
  // The leading digits of the last stamp, kept: most stamps share them with the one before.
  std::int64_t stamp_high_ = -1;  // its value divided by kStampLow
  std::array<char, 24> stamp_high_text_{};
  std::size_t stamp_high_size_ = 0;
  bool started_ = false;
  bool finished_ = false;
};

}  // namespace endatsim::sim

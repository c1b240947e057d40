// What the text capture readers (VCD, CSV) share: the file's size, the signals, which of them are
// selected, the last level reported for each, and the changes decoded but not yet handed out.
// A reader decodes a piece of its file at a time (refill) and hands its level changes to emit.
#pragma once

#include <string>
#include <vector>

#include "endatsim/capture/capture.hpp"

namespace endatsim::capture {

class QueuedReader : public Reader {
 public:
  const std::vector<std::string>& signals() const override { return signals_; }
  Time resolution() const override { return resolution_; }
  bool sampled() const override { return sampled_; }
  void select(const std::vector<std::uint32_t>& wanted) override;
  const std::string& path() const override { return path_; }
  std::uint64_t bytes_total() const override { return size_; }
  bool next(Change& change) override;

 protected:
  // Refuses what is not a readable regular file.
  explicit QueuedReader(const std::string& path);
  // Decodes more of the file, handing its changes to emit(); false at the end of the file.
  virtual bool refill() = 0;
  // Once the signals are known: every signal selected, no level reported yet.
  void reset_levels();
  // A level of `signal` at `time`; only a selected signal's changes are handed out.
  void emit(Time time, std::uint32_t signal, char value);

  std::string path_;
  std::uint64_t size_ = 0;
  std::vector<std::string> signals_;
  Time resolution_{1};
  bool sampled_ = false;

 private:
  std::vector<bool> selected_;
  std::vector<char> last_;
  std::vector<Change> queue_;
  std::size_t queue_at_ = 0;
};

}  // namespace endatsim::capture

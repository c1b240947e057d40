#include "endatsim/capture/queued_reader.hpp"

#include <cerrno>
#include <cstring>
#include <sys/stat.h>

namespace endatsim::capture {

QueuedReader::QueuedReader(const std::string& path) : path_(path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw CaptureError(path + ": cannot open the capture for reading: " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw CaptureError(path + ": not a regular file");
  size_ = static_cast<std::uint64_t>(st.st_size);
}

void QueuedReader::select(const std::vector<std::uint32_t>& wanted) {
  selected_.assign(signals_.size(), false);
  for (auto i : wanted)
    if (i < selected_.size()) selected_[i] = true;
}

bool QueuedReader::next(Change& change) {
  while (queue_at_ == queue_.size()) {
    queue_.clear();
    queue_at_ = 0;
    if (!refill()) return false;
  }
  change = queue_[queue_at_++];
  return true;
}

void QueuedReader::reset_levels() {
  selected_.assign(signals_.size(), true);
  last_.assign(signals_.size(), '?');
}

void QueuedReader::emit(Time time, std::uint32_t signal, char value) {
  if (!selected_[signal] || last_[signal] == value) return;
  last_[signal] = value;
  queue_.push_back({time, signal, value});
}

}  // namespace endatsim::capture

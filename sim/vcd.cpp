#include "endatsim/sim/vcd.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <bit>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <map>
#include <stdexcept>

namespace endatsim::sim {
namespace {

std::string short_id(std::size_t index) {
  // Printable identifiers '!'..'~', as short as possible.
  std::string id;
  do {
    id += static_cast<char>('!' + index % 94);
    index /= 94;
  } while (index > 0);
  return id;
}

// A stamp's last kStampLowDigits digits are formatted in a fixed width; the digits before them
// change far less often (every 100 us) and are kept as text (VcdWriter::stamp_high_text_).
constexpr std::int64_t kStampLow = 100'000'000;
constexpr std::size_t kStampLowDigits = 8;

// v < 10^8 as its eight decimal digits, leading zeros included, in the bytes of one word in
// memory order. Every step works on all lanes of the word at once: v splits into two 32-bit
// lanes of four digits (v / 10^4, v % 10^4), each of those into two 16-bit lanes of two digits,
// each of those into two bytes of one digit. x * 10486 >> 20 is x / 100 for every x < 10^4 and
// y * 103 >> 10 is y / 10 for every y < 100; no lane's product reaches into the next. A run
// with a VCD writes a stamp for every other event, so this is a dozen instructions where two
// digits at a time from a table took three dozen.
std::uint64_t eight_digits(std::uint32_t v) {
  const std::uint64_t fours = (v / 10000) | (std::uint64_t{v % 10000} << 32);
  const std::uint64_t hundreds = ((fours * 10486) >> 20) & 0x0000007F0000007FULL;
  const std::uint64_t twos = hundreds | ((fours - 100 * hundreds) << 16);
  const std::uint64_t tens = ((twos * 103) >> 10) & 0x000F000F000F000FULL;
  std::uint64_t digits = tens | ((twos - 10 * tens) << 8) | 0x3030303030303030ULL;  // '0' in every byte
  if constexpr (std::endian::native == std::endian::big) digits = __builtin_bswap64(digits);
  return digits;
}
static_assert(std::endian::native == std::endian::little || std::endian::native == std::endian::big);

}  // namespace

VcdWriter::VcdWriter(Kernel& kernel, const std::string& path) : kernel_(kernel), file_(nullptr), path_(path) {
  // "-" is standard output (a stream of its own, so that closing it leaves the program's); a
  // character device (/dev/null) is written directly; a file through its part file.
  struct stat st {};
  const bool to_stdout = path == "-";
  const bool device = to_stdout || (::stat(path.c_str(), &st) == 0 && S_ISCHR(st.st_mode));
  if (!device) part_ = path + ".part-" + std::to_string(::getpid());
  errno = 0;
  if (to_stdout) {
    const int fd = ::dup(STDOUT_FILENO);
    file_ = fd < 0 ? nullptr : ::fdopen(fd, "wb");
    if (file_ == nullptr && fd >= 0) ::close(fd);
  } else {
    // A part file is created afresh, never through a link planted in its place.
    const int flags = device ? O_WRONLY | O_CLOEXEC : O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC;
    const int fd = ::open(device ? path.c_str() : part_.c_str(), flags, 0666);
    file_ = fd < 0 ? nullptr : ::fdopen(fd, "wb");
    if (file_ == nullptr && fd >= 0) ::close(fd);
  }
  if (file_ == nullptr)
    throw std::runtime_error("cannot open VCD file '" + path + "' for writing: " + std::strerror(errno));
  // One large buffer of our own, written with one call when full: the stream's own buffer
  // would only copy it again.
  std::setvbuf(file_, nullptr, _IONBF, 0);
  buffer_.resize(kBufferSize);
}

void VcdWriter::make_room(std::size_t n) {
  write_buffer();
  if (used_ + n > buffer_.size()) buffer_.resize(used_ + n);
}

VcdWriter::~VcdWriter() {
  if (file_ != nullptr) std::fclose(file_);
  if (!part_.empty()) std::remove(part_.c_str());
}

void VcdWriter::add(Signal& signal, const std::string& scope, const std::string& name) {
  if (started_) throw std::logic_error("VcdWriter::add after start");
  const std::size_t index = probes_.size();
  probes_.push_back(Probe{this, index, &signal, scope, name, short_id(index), signal.read(), false, {}, 0});
  Probe& p = probes_.back();
  if (p.id.size() + 2 > p.line.size()) throw std::logic_error("VcdWriter::add: too many signals");
  p.line_size = p.id.size() + 2;
  std::memcpy(p.line.data() + 1, p.id.data(), p.id.size());
  p.line[p.line_size - 1] = '\n';
  probe_of_.emplace(&p, index);
  signal.on_change_monitor(Action{&VcdWriter::on_change, &p, 0});
}

std::size_t VcdWriter::add_text(const std::string& scope, const std::string& name) {
  if (started_) throw std::logic_error("VcdWriter::add_text after start");
  texts_.push_back(TextProbe{scope, name, "", "-", false});
  return texts_.size() - 1;
}

void VcdWriter::set_text(std::size_t handle, const std::string& text) {
  if (!started_ || finished_) return;
  TextProbe& t = texts_.at(handle);
  // One token: each run of white space becomes one '_'.
  t.pending.clear();
  for (char c : text) {
    const bool space = c == ' ' || c == '\t' || c == '\n' || c == '\r';
    if (!space) t.pending += c;
    else if (!t.pending.empty() && t.pending.back() != '_') t.pending += '_';
  }
  if (t.pending.empty()) t.pending = "-";
  t.dirty = true;
  texts_dirty_ = true;
}

void VcdWriter::start() {
  std::string head = "$version endatsim $end\n$timescale 1ps $end\n";
  for (std::size_t k = 0; k < texts_.size(); ++k) texts_[k].id = short_id(probes_.size() + k);
  std::map<std::string, std::vector<std::string>> scopes;
  for (const Probe& p : probes_) scopes[p.scope].push_back("$var wire 1 " + p.id + " " + p.name + " $end\n");
  for (const TextProbe& t : texts_) scopes[t.scope].push_back("$var string 1 " + t.id + " " + t.name + " $end\n");
  for (const auto& [scope, vars] : scopes) {
    head += "$scope module " + scope + " $end\n";
    for (const auto& v : vars) head += v;
    head += "$upscope $end\n";
  }
  head += "$enddefinitions $end\n#" + std::to_string(kernel_.now().count()) + "\n$dumpvars\n";
  stamped_ = kernel_.now();
  for (Probe& p : probes_) {
    p.written = p.signal->read();
    head += (p.written ? '1' : '0') + p.id + "\n";
  }
  for (const TextProbe& t : texts_) head += "s" + t.pending + " " + t.id + "\n";
  head += "$end\n";
  append(head);
  kernel_.on_time_step_end(Action{&VcdWriter::on_step_end, this, 0});
  started_ = true;
}

void VcdWriter::on_change(void* probe, std::uint64_t) {
  auto& p = *static_cast<Probe*>(probe);
  VcdWriter* w = p.owner;
  if (!p.dirty && w->started_ && !w->finished_) {
    p.dirty = true;
    w->dirty_.push_back(&p);
  }
}

void VcdWriter::on_step_end(void* self, std::uint64_t) {
  auto* w = static_cast<VcdWriter*>(self);
  if (w->dirty_.empty() && !w->texts_dirty_) return;
  const Time now = w->kernel_.now();
  w->write_texts(now);
  for (Probe* probe : w->dirty_) {
    Probe& p = *probe;
    p.dirty = false;
    const bool v = p.signal->read();
    if (v == p.written) continue;  // changed and changed back within the step
    w->stamp_once(now);
    p.written = v;
    p.line[0] = v ? '1' : '0';
    // All of the line's array in one fixed-size copy (a move, not a call); only its line counts.
    std::memcpy(w->room(p.line.size()), p.line.data(), p.line.size());
    w->used_ += p.line_size;
  }
  w->dirty_.clear();
  w->flush_if_full();
}

void VcdWriter::write_texts(Time now) {
  if (!texts_dirty_) return;
  stamp_once(now);
  for (TextProbe& t : texts_) {
    if (!t.dirty) continue;
    t.dirty = false;
    append("s" + t.pending + " " + t.id + "\n");
  }
  texts_dirty_ = false;
}

void VcdWriter::stamp_once(Time now) {
  if (stamped_ == now) return;
  stamp(now);
  stamped_ = now;
}

VcdWriter::Stretch VcdWriter::prepare(const Tape& tape, Time origin) const {
  // What on_change() and on_step_end() do with the tape's changes, with the values the probes'
  // lines were written with followed from the tape: before a probe's first change on it, the
  // opposite of that change (a tape holds changes only, and the writer was quiet when it began).
  Stretch s;
  std::vector<std::int8_t> written(probes_.size(), -1);  // -1: no change of the probe yet
  std::vector<bool> value(probes_.size()), dirty(probes_.size());
  std::vector<std::size_t> order;  // the probes changed in the current time step, in order
  for (std::size_t k = 0; k < tape.items.size(); ++k) {
    const TapeItem& item = tape.items[k];
    if (item.kind == TapeItem::Kind::Monitor) {
      const auto found = probe_of_.find(static_cast<const SignalBase*>(item.who)->listener_of(item.index));
      if (found == probe_of_.end()) continue;
      const std::size_t probe = found->second;
      if (written[probe] < 0) written[probe] = item.value != 0 ? 0 : 1;
      value[probe] = item.value != 0;
      if (!dirty[probe]) order.push_back(probe);
      dirty[probe] = true;
    } else if (item.kind == TapeItem::Kind::StepEnd) {
      Stretch::Step step{item.at - origin, static_cast<std::uint32_t>(s.lines.size()), 0};
      for (std::size_t probe : order) {
        dirty[probe] = false;
        if (static_cast<std::int8_t>(value[probe]) == written[probe]) continue;
        written[probe] = static_cast<std::int8_t>(value[probe]);
        const Probe& p = probes_[probe];
        s.lines += value[probe] ? '1' : '0';
        s.lines.append(p.line.data() + 1, p.line_size - 1);
      }
      order.clear();
      step.end = static_cast<std::uint32_t>(s.lines.size());
      s.steps.push_back(step);
      s.covered = k + 1;
    }
  }
  for (std::size_t probe = 0; probe < probes_.size(); ++probe)
    if (written[probe] >= 0) s.written.emplace_back(probe, written[probe] != 0);
  return s;
}

void VcdWriter::play_steps(const Stretch& stretch, std::size_t first, std::size_t last, Time origin) {
  if (!started_ || finished_ || first == last) return;
  write_texts(origin + stretch.steps[first].at);
  for (std::size_t k = first; k < last; ++k) {
    const Stretch::Step& s = stretch.steps[k];
    if (s.end == s.begin) continue;
    stamp_once(origin + s.at);
    append(stretch.lines.data() + s.begin, s.end - s.begin);
    flush_if_full();
  }
}

void VcdWriter::play_end(const Stretch& stretch) {
  for (const auto& [probe, value] : stretch.written) probes_[probe].written = value;
}

void VcdWriter::stamp(Time at) {
  constexpr std::size_t kStamp = 24;  // '#', at most 20 digits, '\n'
  char* text = room(kStamp);
  text[0] = '#';
  char* end = text + 1;
  const std::int64_t t = at.count();
  if (t < kStampLow) {
    end = std::to_chars(end, text + kStamp - 1, t).ptr;
  } else {
    const std::int64_t high = t / kStampLow;
    if (high != stamp_high_) {
      stamp_high_ = high;
      stamp_high_size_ = static_cast<std::size_t>(
          std::to_chars(stamp_high_text_.data(), stamp_high_text_.data() + stamp_high_text_.size(), high).ptr -
          stamp_high_text_.data());
    }
    std::memcpy(end, stamp_high_text_.data(), 16);  // fixed size: the digits and what follows, overwritten below
    end += stamp_high_size_;
    const std::uint64_t low = eight_digits(static_cast<std::uint32_t>(t - high * kStampLow));
    static_assert(sizeof low == kStampLowDigits);
    std::memcpy(end, &low, kStampLowDigits);
    end += kStampLowDigits;
  }
  *end = '\n';
  used_ += static_cast<std::size_t>(end + 1 - text);
}

void VcdWriter::flush_if_full() {
  if (used_ < kBufferSize - 4096) return;
  write_buffer();
}

void VcdWriter::write_buffer() {
  if (file_ == nullptr) {  // a write failed before: finish() says so
    used_ = 0;
    return;
  }
  errno = 0;
  if (std::fwrite(buffer_.data(), 1, used_, file_) != used_) {
    const int error = errno;
    std::fclose(file_);
    file_ = nullptr;
    throw std::runtime_error("write error on VCD file '" + path_ + "': " + (error != 0 ? std::strerror(error) : "short write"));
  }
  used_ = 0;
}

void VcdWriter::finish() {
  if (finished_) return;
  finished_ = true;
  if (stamped_ != kernel_.now()) stamp(kernel_.now());
  write_buffer();
  if (file_ == nullptr) throw std::runtime_error("write error on VCD file '" + path_ + "'");
  errno = 0;
  const int closed = std::fclose(file_);
  const int error = errno;
  file_ = nullptr;
  if (closed != 0)
    throw std::runtime_error("write error on VCD file '" + path_ + "': " + (error != 0 ? std::strerror(error) : "close failed"));
  if (part_.empty()) return;
  if (std::rename(part_.c_str(), path_.c_str()) != 0)
    throw std::runtime_error("cannot write VCD file '" + path_ + "': " + std::strerror(errno));
  part_.clear();
}

}  // namespace endatsim::sim

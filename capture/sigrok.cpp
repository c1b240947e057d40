// sigrok session files (.sr) as PulseView and sigrok-cli save them (sigrok session file format,
// versions 1 and 2): a zip archive holding
//   version     "2" (or "1": the same logic layout, without analog channels)
//   metadata    INI-like; the [device 1] section names the logic data and its layout:
//                 capturefile=logic-1   the base name of the sample entries (absent: analog only)
//                 total probes=N        logic channels in each sample
//                 samplerate=25 MHz     also "100 kHz", "1 GHz", "1.5 MHz", "200 Hz"
//                 probeK=name           the name of channel K (1-based); unnamed ones were disabled
//                 unitsize=U            bytes per sample
//   logic-1-1, logic-1-2, ...   the samples in order: U-byte little-endian words, bit K-1 = probe K
//                               (a single unchunked "logic-1" is read too)
// Analog channels (analog-1-K-N entries) are ignored. The chunks are read through libzip in
// bounded pieces, so memory does not depend on the length of the capture.
#include <cerrno>
#include <cstring>
#include <zip.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <fstream>
#include <map>
#include <set>
#include <sys/stat.h>

#include "endatsim/capture/capture.hpp"
#include "endatsim/sim/text.hpp"

namespace endatsim::capture {
namespace {

using sim::kPsPerSecond;
constexpr zip_uint64_t kMaxMetadata = 1 << 20;

std::string trim(const std::string& s) { return std::string(sim::trim(s)); }

bool whole_number(const std::string& s, std::uint64_t& out) {
  const auto v = sim::whole_number(s);
  if (v) out = *v;
  return v.has_value();
}

std::string zip_message(int code) {
  zip_error_t error;
  zip_error_init_with_code(&error, code);
  std::string text = zip_error_strerror(&error);
  zip_error_fini(&error);
  return text;
}

class SigrokReader final : public Reader {
 public:
  explicit SigrokReader(const std::string& path) : path_(path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) throw CaptureError(path + ": cannot open the capture for reading: " + std::strerror(errno));
    if (!S_ISREG(st.st_mode)) throw CaptureError(path + ": not a regular file");
    size_ = static_cast<std::uint64_t>(st.st_size);
    int code = 0;
    zip_ = zip_open(path.c_str(), ZIP_RDONLY | ZIP_CHECKCONS, &code);
    if (zip_ == nullptr) {
      if (code == ZIP_ER_NOZIP && !starts_like_zip(path))
        throw CaptureError(path + ": not a zip archive; a sigrok session file (.sr) is a zip holding 'version', "
                           "'metadata' and the sample entries 'logic-1-1', ...");
      if (code == ZIP_ER_NOZIP)
        throw CaptureError(path + ": a zip archive without its central directory at the end (truncated?); a sigrok "
                           "session file (.sr) is a complete zip holding 'version', 'metadata' and 'logic-1-1', ...");
      throw CaptureError(path + ": cannot read it as a zip archive (" + zip_message(code) +
                         "; truncated or corrupt?); a sigrok session file (.sr) is a zip holding 'version', "
                         "'metadata' and 'logic-1-1', ...");
    }
    try {
      metadata();
      find_chunks();
    } catch (...) {
      zip_discard(zip_);
      throw;
    }
    selected_ = all_bits_;
    buffer_.resize(static_cast<std::size_t>(unitsize_) * 8192);
  }

  ~SigrokReader() override {
    if (file_ != nullptr) zip_fclose(file_);
    zip_discard(zip_);
  }
  SigrokReader(const SigrokReader&) = delete;
  SigrokReader& operator=(const SigrokReader&) = delete;

  const std::vector<std::string>& signals() const override { return signals_; }
  Time resolution() const override { return resolution_; }
  bool sampled() const override { return true; }
  void select(const std::vector<std::uint32_t>& wanted) override {
    selected_ = 0;
    for (auto i : wanted)
      if (i < bits_.size()) selected_ |= std::uint64_t{1} << bits_[i];
  }
  const std::string& path() const override { return path_; }
  std::uint64_t bytes_read() const override {
    // Compressed bytes of the chunks done, and the part of the current one read so far.
    std::uint64_t done = done_compressed_;
    if (chunk_ < chunks_.size() && chunks_[chunk_].size > 0)
      done += static_cast<std::uint64_t>(static_cast<unsigned __int128>(chunks_[chunk_].compressed) * chunk_read_ /
                                         chunks_[chunk_].size);
    return std::min(done, size_);
  }
  std::uint64_t bytes_total() const override { return size_; }
  Time end() const override { return sample_ == 0 ? Time::zero() : time_of(sample_ - 1); }

  bool next(Change& change) override {
    while (queue_at_ == queue_.size()) {
      queue_.clear();
      queue_at_ = 0;
      if (!scan()) return false;
    }
    change = queue_[queue_at_++];
    return true;
  }

 private:
  struct Chunk {
    zip_uint64_t index = 0;
    std::string name;
    zip_uint64_t size = 0;        // uncompressed bytes
    zip_uint64_t compressed = 0;  // bytes in the archive
  };

  [[noreturn]] void fail(const std::string& what) const { throw CaptureError(path_ + ": " + what); }

  // The whole of a small entry (version, metadata); false when the archive has none.
  bool read_small(const char* name, std::string& out) {
    const zip_int64_t index = zip_name_locate(zip_, name, 0);
    if (index < 0) return false;
    zip_stat_t st;
    zip_stat_init(&st);
    if (zip_stat_index(zip_, static_cast<zip_uint64_t>(index), 0, &st) != 0 || (st.valid & ZIP_STAT_SIZE) == 0)
      fail(std::string("entry '") + name + "': " + zip_strerror(zip_));
    if (st.size > kMaxMetadata) fail(std::string("entry '") + name + "' is " + std::to_string(st.size) +
                                     " bytes; expected a small text (at most 1 MiB)");
    zip_file_t* file = zip_fopen_index(zip_, static_cast<zip_uint64_t>(index), 0);
    if (file == nullptr) fail(std::string("entry '") + name + "': " + zip_strerror(zip_));
    out.assign(static_cast<std::size_t>(st.size), '\0');
    zip_uint64_t got = 0;
    while (got < st.size) {
      const zip_int64_t n = zip_fread(file, out.data() + got, st.size - got);
      if (n < 0) {
        const std::string why = zip_error_strerror(zip_file_get_error(file));
        zip_fclose(file);
        fail(std::string("entry '") + name + "': " + why + " (truncated or corrupt zip?)");
      }
      if (n == 0) break;
      got += static_cast<zip_uint64_t>(n);
    }
    zip_fclose(file);
    if (got != st.size) fail(std::string("entry '") + name + "' ends early (truncated or corrupt zip?)");
    return true;
  }

  void metadata() {
    std::string text;
    if (!read_small("metadata", text))
      fail("a zip archive without a 'metadata' entry: not a sigrok session file (expected the entries 'version', "
           "'metadata' and 'logic-1-1', ... as PulseView and sigrok-cli save them)");
    std::string version;
    if (!read_small("version", version))
      fail("a zip archive without a 'version' entry: not a sigrok session file (expected 'version' holding 2)");
    version = trim(version);
    if (version != "1" && version != "2")
      fail("sigrok session file version '" + version.substr(0, 20) + "'; expected version 1 or 2");

    // Sections and their keys; the logic data belongs to the device section with a capturefile.
    std::map<std::string, std::map<std::string, std::string>> sections;
    std::map<std::string, std::size_t> section_line;
    std::string section;
    std::size_t line_no = 0;
    for (std::size_t at = 0; at <= text.size();) {
      std::size_t end = text.find('\n', at);
      if (end == std::string::npos) end = text.size();
      const std::string line = trim(text.substr(at, end - at));
      at = end + 1;
      ++line_no;
      if (line.empty() || line[0] == '#' || line[0] == ';') continue;
      if (line.front() == '[') {
        if (line.back() != ']') fail("metadata: line " + std::to_string(line_no) + ": '" + line.substr(0, 40) +
                                     "' where a [section] was expected");
        section = trim(line.substr(1, line.size() - 2));
        section_line.emplace(section, line_no);
        sections[section];
        continue;
      }
      const auto eq = line.find('=');
      if (eq == std::string::npos || section.empty())
        fail("metadata: line " + std::to_string(line_no) + ": '" + line.substr(0, 40) +
             "' where key=value inside a [section] was expected");
      sections[section][trim(line.substr(0, eq))] = trim(line.substr(eq + 1));
    }
    const std::map<std::string, std::string>* device = nullptr;
    std::string device_name;
    bool any_device = false;
    for (const auto& [name, keys] : sections) {
      if (name.rfind("device ", 0) != 0) continue;
      any_device = true;
      if (keys.count("capturefile") == 0) continue;
      if (device != nullptr) fail("metadata: logic data in both [" + device_name + "] and [" + name +
                                  "]; expected one device with a capturefile");
      device = &keys;
      device_name = name;
    }
    if (!any_device) fail("metadata: no [device 1] section; expected one with capturefile, samplerate, total probes, "
                          "probe1=..., unitsize");
    if (device == nullptr)
      fail("metadata: no capturefile in any [device] section: an analog-only session; expected logic channels "
           "(capturefile=logic-1)");
    const auto& keys = *device;
    const std::string where = "metadata [" + device_name + "]: ";
    auto value = [&](const std::string& key) -> const std::string* {
      const auto it = keys.find(key);
      return it == keys.end() ? nullptr : &it->second;
    };

    capturefile_ = *value("capturefile");
    if (capturefile_.empty()) fail(where + "empty capturefile; expected the base name of the sample entries (logic-1)");

    const std::string* rate = value("samplerate");
    if (rate == nullptr) fail(where + "no samplerate; expected e.g. samplerate=25 MHz");
    samplerate_ = parse_samplerate(*rate, where);
    const std::int64_t whole = kPsPerSecond / samplerate_;
    // A period that is no whole number of picoseconds rounds up: no finer than the true one.
    resolution_ = Time{std::max<std::int64_t>(1, whole + (kPsPerSecond % samplerate_ != 0 ? 1 : 0))};

    const std::string* total_text = value("total probes");
    std::uint64_t total = 0;
    if (total_text == nullptr || !whole_number(*total_text, total) || total == 0 || total > 64)
      fail(where + "total probes is " + (total_text ? "'" + total_text->substr(0, 20) + "'" : "missing") +
           "; expected the number of logic channels, 1 .. 64");

    const std::string* unit_text = value("unitsize");
    std::uint64_t unitsize = 0;
    if (unit_text == nullptr) {
      unitsize = (total + 7) / 8;  // version 1 files may leave it out: the fewest bytes that hold the channels
    } else if (!whole_number(*unit_text, unitsize) || unitsize < 1 || unitsize > 8) {
      fail(where + "unitsize '" + unit_text->substr(0, 20) + "'; expected 1 .. 8 bytes per sample");
    }
    unitsize_ = static_cast<unsigned>(unitsize);
    if (total > unitsize * 8)
      fail(where + "total probes=" + std::to_string(total) + " do not fit unitsize=" + std::to_string(unitsize) +
           " (" + std::to_string(unitsize * 8) + " bits); expected total probes <= 8 x unitsize");

    // probeK=name for the enabled channels, in probe order.
    std::map<std::uint64_t, std::string> probes;
    for (const auto& [key, name] : keys) {
      if (key.rfind("probe", 0) != 0) continue;
      std::uint64_t k = 0;
      if (!whole_number(key.substr(5), k)) continue;
      if (k < 1 || k > total)
        fail(where + key + "=" + name.substr(0, 40) + " but total probes=" + std::to_string(total) +
             "; expected probe1 .. probe" + std::to_string(total));
      if (name.empty()) fail(where + key + " has no name");
      probes[k] = name;
    }
    if (probes.empty())
      fail(where + "no probeK=name entries; expected a name for each captured logic channel (probe1=...)");
    std::set<std::string> seen;
    for (const auto& [k, name] : probes) {
      if (!seen.insert(name).second) fail(where + "two probes named '" + name + "'; expected distinct names");
      signals_.push_back(name);
      bits_.push_back(static_cast<unsigned>(k - 1));
      all_bits_ |= std::uint64_t{1} << (k - 1);
    }
  }

  // "25 MHz", "1.5 MHz", "100 kHz", "1 GHz", "200 Hz", or a bare number of hertz.
  std::int64_t parse_samplerate(const std::string& text, const std::string& where) const {
    std::uint64_t bare = 0;
    std::int64_t hz = 0;
    if (whole_number(text, bare)) {
      if (bare > static_cast<std::uint64_t>(INT64_MAX) / 2) fail(where + "samplerate '" + text + "' is too large");
      hz = static_cast<std::int64_t>(bare);
    } else {
      try {
        hz = sim::parse_frequency(text);
      } catch (const std::invalid_argument& e) {
        fail(where + "samplerate '" + text.substr(0, 40) + "': " + e.what());
      }
    }
    if (hz <= 0) fail(where + "samplerate '" + text.substr(0, 40) + "'; expected a positive rate such as 25 MHz");
    return hz;
  }

  // capturefile-1, capturefile-2, ... without gaps, or the unchunked capturefile alone.
  void find_chunks() {
    const zip_int64_t entries = zip_get_num_entries(zip_, 0);
    const std::string prefix = capturefile_ + "-";
    std::map<std::uint64_t, Chunk> numbered;
    for (zip_int64_t i = 0; i < entries; ++i) {
      const char* raw = zip_get_name(zip_, static_cast<zip_uint64_t>(i), 0);
      if (raw == nullptr) continue;
      const std::string name = raw;
      std::uint64_t n = 0;
      if (name == capturefile_) {
        numbered[0] = stat_chunk(static_cast<zip_uint64_t>(i), name);
      } else if (name.rfind(prefix, 0) == 0 && whole_number(name.substr(prefix.size()), n) && n > 0) {
        numbered[n] = stat_chunk(static_cast<zip_uint64_t>(i), name);
      }
    }
    if (numbered.count(0) != 0 && numbered.size() > 1)
      fail("both an unchunked '" + capturefile_ + "' and chunks '" + prefix + "N'; expected one or the other");
    std::uint64_t expect = numbered.count(0) != 0 ? 0 : 1;
    for (auto& [n, chunk] : numbered) {
      if (n != expect)
        fail("entry '" + chunk.name + "' follows a missing '" + prefix + std::to_string(expect) +
             "'; expected the chunks numbered from 1 without gaps");
      ++expect;
      chunks_.push_back(chunk);
    }
    if (chunks_.empty())
      fail("no sample data: expected the entries '" + prefix + "1', '" + prefix + "2', ... named by capturefile=" +
           capturefile_);
  }

  Chunk stat_chunk(zip_uint64_t index, const std::string& name) {
    zip_stat_t st;
    zip_stat_init(&st);
    if (zip_stat_index(zip_, index, 0, &st) != 0 || (st.valid & ZIP_STAT_SIZE) == 0)
      fail("entry '" + name + "': " + zip_strerror(zip_));
    if (st.size % unitsize_ != 0)
      fail("entry '" + name + "' holds " + std::to_string(st.size) + " bytes, not a whole number of samples of unitsize=" +
           std::to_string(unitsize_) + "; expected a multiple of " + std::to_string(unitsize_));
    Chunk c;
    c.index = index;
    c.name = name;
    c.size = st.size;
    c.compressed = (st.valid & ZIP_STAT_COMP_SIZE) != 0 ? st.comp_size : st.size;
    return c;
  }

  // Fills the buffer from the current chunk (opening the next one as needed); false at the end.
  bool fill() {
    while (true) {
      if (chunk_ == chunks_.size()) return false;
      const Chunk& c = chunks_[chunk_];
      if (file_ == nullptr) {
        file_ = zip_fopen_index(zip_, c.index, 0);
        if (file_ == nullptr) fail("entry '" + c.name + "': " + zip_strerror(zip_));
        chunk_read_ = 0;
      }
      const zip_int64_t n = zip_fread(file_, buffer_.data() + carry_, buffer_.size() - carry_);
      if (n < 0)
        fail("entry '" + c.name + "': " + zip_error_strerror(zip_file_get_error(file_)) +
             " after " + std::to_string(chunk_read_) + " of its " + std::to_string(c.size) +
             " bytes (truncated or corrupt zip entry)");
      if (n > 0) {
        chunk_read_ += static_cast<zip_uint64_t>(n);
        if (chunk_read_ > c.size) fail("entry '" + c.name + "' holds more bytes than the zip directory says (corrupt zip)");
        end_ = carry_ + static_cast<std::size_t>(n);
        // A sample cut by the end of a read waits for the rest.
        const std::size_t whole = end_ - end_ % unitsize_;
        if (whole == 0) {
          carry_ = end_;
          continue;
        }
        pos_ = 0;
        limit_ = whole;
        return true;
      }
      if (chunk_read_ != c.size)
        fail("entry '" + c.name + "' ends after " + std::to_string(chunk_read_) + " of its " + std::to_string(c.size) +
             " bytes (truncated or corrupt zip entry)");
      if (carry_ != 0) fail("entry '" + c.name + "' ends inside a sample");
      zip_fclose(file_);
      file_ = nullptr;
      done_compressed_ += c.compressed;
      ++chunk_;
    }
  }

  // Scans samples until one changes a selected channel (its changes are queued); false at the end.
  bool scan() {
    while (true) {
      if (pos_ == limit_) {
        // Keep the bytes of a cut sample at the front of the buffer.
        const std::size_t rest = end_ - limit_;
        std::copy(buffer_.begin() + static_cast<std::ptrdiff_t>(limit_), buffer_.begin() + static_cast<std::ptrdiff_t>(end_),
                  buffer_.begin());
        carry_ = rest;
        pos_ = limit_ = end_ = 0;
        if (!fill()) return false;
        carry_ = 0;
      }
      const unsigned char* p = buffer_.data();
      for (; pos_ < limit_; pos_ += unitsize_, ++sample_) {
        std::uint64_t v = 0;
        for (unsigned b = 0; b < unitsize_; ++b) v |= static_cast<std::uint64_t>(p[pos_ + b]) << (8 * b);
        const std::uint64_t changed = ((v ^ reported_) | ~known_) & selected_;
        if (changed == 0) continue;
        const Time at = time_of(sample_);
        for (std::uint32_t i = 0; i < bits_.size(); ++i) {
          const std::uint64_t bit = std::uint64_t{1} << bits_[i];
          if ((changed & bit) != 0) queue_.push_back({at, i, (v & bit) != 0 ? '1' : '0'});
        }
        reported_ = (reported_ & ~changed) | (v & changed);
        known_ |= changed;
        pos_ += unitsize_;
        ++sample_;
        return true;
      }
    }
  }

  Time time_of(std::uint64_t sample) const {
    const auto t = static_cast<unsigned __int128>(sample) * kPsPerSecond / static_cast<unsigned __int128>(samplerate_);
    if (t > static_cast<unsigned __int128>(INT64_MAX)) fail("sample " + std::to_string(sample) + " lies beyond the picosecond range");
    return Time{static_cast<std::int64_t>(t)};
  }

  std::string path_;
  std::uint64_t size_ = 0;
  zip_t* zip_ = nullptr;
  std::string capturefile_;
  std::int64_t samplerate_ = 0;
  Time resolution_{1};
  unsigned unitsize_ = 1;
  std::vector<std::string> signals_;
  std::vector<unsigned> bits_;  // the sample bit of each signal
  std::uint64_t all_bits_ = 0;
  std::uint64_t selected_ = 0;
  std::uint64_t reported_ = 0;  // the levels reported so far
  std::uint64_t known_ = 0;     // the bits whose level has been reported
  std::vector<Chunk> chunks_;
  std::size_t chunk_ = 0;
  zip_file_t* file_ = nullptr;
  zip_uint64_t chunk_read_ = 0;
  std::uint64_t done_compressed_ = 0;
  std::vector<unsigned char> buffer_;
  std::size_t carry_ = 0;  // bytes of a cut sample at the buffer's front, during fill()
  std::size_t pos_ = 0, limit_ = 0, end_ = 0;
  std::uint64_t sample_ = 0;
  std::vector<Change> queue_;
  std::size_t queue_at_ = 0;
};

}  // namespace

std::unique_ptr<Reader> open_sigrok(const std::string& path) { return std::make_unique<SigrokReader>(path); }

}  // namespace endatsim::capture

// libFuzzer targets for the capture readers, built three times from this file with
// ENDATSIM_FUZZ_CAPTURE set to the format:
//   fuzz_capture_vcd     the bytes as a .vcd, read with open_vcd
//   fuzz_capture_csv     the bytes as a .csv, read with open_csv
//   fuzz_capture_sigrok  a .sr for open_sigrok: bytes that begin like a zip ("PK\3\4") are the
//                        file as they are; any other bytes are entries separated by a 0x1E byte,
//                        each its name up to the first newline and then its content, stored into
//                        a zip here (so that mutations reach the metadata and the samples rather
//                        than fail the zip's checksums)
// The readers take a path: the bytes go to a file in a directory private to the process (mkdtemp,
// mode 0700, under $TMPDIR or /tmp), named by mkstemps, and removed at exit and when a bug is
// reported (not when libFuzzer ends a run for a timeout or too much memory; fuzz/run points
// TMPDIR at its scratch directory). Every signal is selected and next() drained (at most 1e6
// changes), and find_signal is asked for a name taken from the input and for one of the signals.
// Only a CaptureError that names the file may come out; anything else (another exception, a
// crash, UB, a leak, a hang, a broken promise of the interface) is a bug.
#include <sanitizer/common_interface_defs.h>
#include <unistd.h>
#include <zip.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "endatsim/capture/capture.hpp"

#ifndef ENDATSIM_FUZZ_CAPTURE
#error "define ENDATSIM_FUZZ_CAPTURE as 1 (VCD), 2 (CSV) or 3 (sigrok)"
#endif

namespace capture = endatsim::capture;

namespace {

constexpr int kVcd = 1, kCsv = 2, kSigrok = 3;
constexpr int kFormat = ENDATSIM_FUZZ_CAPTURE;
constexpr std::uint64_t kMaxChanges = 1'000'000;

std::string private_dir;
std::string current_file;  // the input's file while it is read

// At exit, and when a sanitizer or this target reports a bug: the file and the directory go.
void remove_private_dir() {
  if (!current_file.empty()) ::unlink(current_file.c_str());
  if (!private_dir.empty()) ::rmdir(private_dir.c_str());
}

[[noreturn]] void bug(const std::string& what) {
  std::fprintf(stderr, "fuzz_capture: %s\n", what.c_str());
  remove_private_dir();
  std::abort();
}

const std::string& dir() {
  if (private_dir.empty()) {
    const char* base = std::getenv("TMPDIR");
    std::string pattern = std::string(base != nullptr && *base != '\0' ? base : "/tmp") + "/fuzz_capture.XXXXXX";
    if (::mkdtemp(pattern.data()) == nullptr) bug("mkdtemp failed: " + std::string(std::strerror(errno)));
    private_dir = pattern;
    std::atexit(remove_private_dir);
    __sanitizer_set_death_callback(remove_private_dir);
  }
  return private_dir;
}

// A new empty file in the private directory with the format's extension; its path.
std::string new_file(int& fd) {
  const char* ext = kFormat == kVcd ? ".vcd" : kFormat == kCsv ? ".csv" : ".sr";
  std::string path = dir() + "/inputXXXXXX" + ext;
  fd = ::mkstemps(path.data(), static_cast<int>(std::strlen(ext)));
  if (fd < 0) bug("mkstemps failed: " + std::string(std::strerror(errno)));
  return path;
}

void write_all(int fd, const std::uint8_t* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n <= 0) bug("cannot write the input: " + std::string(std::strerror(errno)));
    data += n;
    size -= static_cast<std::size_t>(n);
  }
}

// Entries separated by 0x1E, each "name\ncontent", stored uncompressed into a zip at `path`.
// False when libzip refuses them (an empty or repeated name): such inputs are not interesting.
bool write_session(const std::string& path, const std::uint8_t* data, std::size_t size) {
  int code = 0;
  zip_t* zip = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &code);
  if (zip == nullptr) bug("zip_open for writing failed: " + std::to_string(code));
  const char* text = reinterpret_cast<const char*>(data);
  bool ok = true;
  for (std::size_t at = 0; at <= size && ok;) {
    const void* sep = std::memchr(text + at, 0x1E, size - at);
    const std::size_t end = sep != nullptr ? static_cast<std::size_t>(static_cast<const char*>(sep) - text) : size;
    const void* nl = std::memchr(text + at, '\n', end - at);
    const std::size_t name_end = nl != nullptr ? static_cast<std::size_t>(static_cast<const char*>(nl) - text) : end;
    const std::string name(text + at, name_end - at);
    const std::size_t content = name_end < end ? name_end + 1 : end;
    zip_source_t* source = zip_source_buffer(zip, text + content, end - content, 0);
    if (source == nullptr) bug("zip_source_buffer failed");
    const zip_int64_t index =
        name.empty() || std::memchr(name.data(), '\0', name.size()) != nullptr ? -1 : zip_file_add(zip, name.c_str(), source, 0);
    if (index < 0) {
      zip_source_free(source);
      ok = false;
    } else if (zip_set_file_compression(zip, static_cast<zip_uint64_t>(index), ZIP_CM_STORE, 0) != 0) {
      bug("zip_set_file_compression failed");
    }
    at = end + 1;
  }
  if (!ok) {
    zip_discard(zip);
    return false;
  }
  if (zip_close(zip) != 0) {
    const std::string why = zip_strerror(zip);
    zip_discard(zip);
    bug("zip_close failed: " + why);
  }
  return true;
}

void read_capture(const std::string& path, const std::uint8_t* data, std::size_t size) {
  std::unique_ptr<capture::Reader> reader;
  if constexpr (kFormat == kVcd) reader = capture::open_vcd(path);
  else if constexpr (kFormat == kCsv) reader = capture::open_csv(path);
  else reader = capture::open_sigrok(path);

  const auto& signals = reader->signals();
  if (signals.empty()) bug("a capture opened without signals");
  if (reader->path() != path) bug("path() is not the file opened");
  if (reader->resolution() <= capture::Time{0}) bug("a resolution that is not positive");
  std::vector<std::uint32_t> all(signals.size());
  for (std::uint32_t i = 0; i < all.size(); ++i) all[i] = i;
  reader->select(all);

  capture::Change change;
  capture::Time last{INT64_MIN};
  for (std::uint64_t n = 0; n < kMaxChanges && reader->next(change); ++n) {
    if (change.signal >= signals.size()) bug("a change of signal " + std::to_string(change.signal) + " of " +
                                             std::to_string(signals.size()));
    if (change.value != '0' && change.value != '1' && change.value != 'x')
      bug(std::string("a change to the value '") + change.value + "'");
    if (change.time < last) bug("changes out of time order");
    last = change.time;
    if (reader->bytes_read() > reader->bytes_total()) bug("bytes_read() beyond bytes_total()");
  }

  // A name from the input: the bytes after its last newline (at most 64).
  std::size_t from = size;
  while (from > 0 && data[from - 1] != '\n' && size - from < 64) --from;
  const std::string name(reinterpret_cast<const char*>(data) + from, size - from);
  try {
    if (capture::find_signal(*reader, name) >= signals.size()) bug("find_signal gave an index past the signals");
  } catch (const capture::CaptureError&) {
  }
  // A signal by its full name is found, unless another of the same name comes first.
  const std::uint32_t pick = static_cast<std::uint32_t>(size % signals.size());
  const std::uint32_t found = capture::find_signal(*reader, signals[pick]);
  if (found >= signals.size() || signals[found] != signals[pick]) bug("find_signal missed '" + signals[pick] + "'");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  int fd = -1;
  const std::string path = new_file(fd);
  current_file = path;
  const bool raw = kFormat != kSigrok || (size >= 4 && std::memcmp(data, "PK\3\4", 4) == 0);
  if (raw) write_all(fd, data, size);
  ::close(fd);
  if (raw || write_session(path, data, size)) {
    try {
      read_capture(path, data, size);
    } catch (const capture::CaptureError& e) {
      if (std::string(e.what()).rfind(path + ": ", 0) != 0) bug("error does not name the file: " + std::string(e.what()));
    }
  }
  ::unlink(path.c_str());
  current_file.clear();
  return 0;
}

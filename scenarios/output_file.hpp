// Output files (results, logs, waveforms) written so that a reader never sees half of one: to a
// part file beside the place, renamed into it when complete; an interrupted run leaves the
// previous file (or none). "-" is standard output; character devices (/dev/null) are written
// directly. Every write and the close are checked; nothing here throws from a destructor.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <streambuf>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace endatsim::scenarios {

// A buffered stream over a file descriptor that keeps the reason of a failed write.
class FdBuffer : public std::streambuf {
 public:
  FdBuffer();
  void attach(int fd) { fd_ = fd; }
  int error() const { return error_; }  // errno of the first failed write, or 0

 protected:
  int_type overflow(int_type c) override;
  int sync() override;

 private:
  bool drain();
  int fd_ = -1;
  int error_ = 0;
  std::string buffer_;
};

// An output written piece by piece; a part file not committed is removed.
class StreamedFile {
 public:
  // Throws std::runtime_error naming the path and the reason when it cannot be opened.
  explicit StreamedFile(const std::string& path);
  StreamedFile(const StreamedFile&) = delete;
  StreamedFile& operator=(const StreamedFile&) = delete;
  ~StreamedFile();
  std::ostream& stream();
  // Flushes, checks every write and the close, and renames the part file into place.
  void commit();
  const std::string& path() const { return path_; }

 private:
  [[noreturn]] void fail(int error) const;
  std::string path_;
  std::string part_;
  int fd_ = -1;
  FdBuffer buffer_;
  std::ostream file_{&buffer_};
};

// The whole text at once, the same way.
void write_file(const std::string& path, const std::string& text);

// A JSON document as a file's text, indented; bytes that are not UTF-8 (a capture's names and
// messages quote what the file holds) become U+FFFD instead of failing the whole output.
inline std::string json_file_text(const nlohmann::json& j) {
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

// An output a command is asked to write: its option ("--json") and its path.
struct OutputPath {
  std::string option;
  std::string path;
  bool directory = false;  // a directory that will hold several files (run --vcd with several scenarios)
};

// Before anything runs: throws std::runtime_error naming the option, the path and the reason when
// an output is one of the inputs (`inputs_are` says what they are: "the scenario file"), when two
// outputs are the same file, when it is a directory (unless expected), a FIFO, a socket or a block
// device, when an existing file is read-only, or when the directory it goes into does not exist or
// cannot be written. Character devices pass; "-" (standard output) passes for one output that is
// a single file.
void check_output_paths(const std::vector<std::string>& inputs, const std::string& inputs_are,
                        const std::vector<OutputPath>& outputs);

// Whether one of the outputs is standard output ("-"): then the summary meant for a person goes
// to standard error, so that standard output holds that output alone.
bool writes_to_stdout(const std::vector<OutputPath>& outputs);

// Standard output checked for a program's whole life (a full disk, `> /dev/full`): std::cout
// keeps its buffering (line by line on a terminal) and the reason of its first failed write is
// kept. finish() flushes it; when a write failed it says so on standard error, naming the program
// and the reason, and returns 2 unless `status` already says worse; otherwise `status`.
class CheckedStdout {
 public:
  explicit CheckedStdout(std::string program);
  ~CheckedStdout();
  CheckedStdout(const CheckedStdout&) = delete;
  CheckedStdout& operator=(const CheckedStdout&) = delete;
  int finish(int status);

 private:
  class Watch;
  std::string program_;
  std::unique_ptr<Watch> watch_;
  std::streambuf* previous_;
};

// Removes what an interrupted command leaves at its output paths (an earlier run's results must not
// stay in place as if current); "-" and devices are left alone. The paths removed.
std::vector<std::string> remove_outputs(const std::vector<OutputPath>& outputs);

}  // namespace endatsim::scenarios

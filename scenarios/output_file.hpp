// Output files (results, logs, waveforms) written so that a reader never sees half of one: to a
// part file beside the place, renamed into it when complete; an interrupted run leaves the
// previous file (or none). "-" is standard output; pipes and devices are written directly.
#pragma once

#include <fstream>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

namespace endatsim::scenarios {

// An output written piece by piece; a part file not committed is removed.
class StreamedFile {
 public:
  // Throws std::runtime_error naming the path and the reason when it cannot be opened.
  explicit StreamedFile(const std::string& path);
  StreamedFile(const StreamedFile&) = delete;
  StreamedFile& operator=(const StreamedFile&) = delete;
  ~StreamedFile();
  std::ostream& stream();
  // Flushes, checks every write, and renames the part file into place.
  void commit();

 private:
  std::string path_;
  std::string part_;
  std::ofstream file_;
};

// The whole text at once, the same way.
void write_file(const std::string& path, const std::string& text);

// A JSON document as a file's text, indented; bytes that are not UTF-8 (a capture's names and
// messages quote what the file holds) become U+FFFD instead of failing the whole output.
inline std::string json_file_text(const nlohmann::json& j) {
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace endatsim::scenarios

#include "scenarios/output_file.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include <unistd.h>

namespace endatsim::scenarios {

StreamedFile::StreamedFile(const std::string& path) : path_(path) {
  if (path == "-") return;
  std::error_code status_error;
  const auto status = std::filesystem::status(path, status_error);
  const bool special = std::filesystem::exists(status) && !std::filesystem::is_regular_file(status);
  if (!special) part_ = path + ".part-" + std::to_string(::getpid());
  file_.open(special ? path : part_, std::ios::binary);
  if (!file_) throw std::runtime_error("cannot write '" + path + "': " + std::strerror(errno));
}

StreamedFile::~StreamedFile() {
  if (part_.empty()) return;
  std::error_code ignored;
  std::filesystem::remove(part_, ignored);
}

std::ostream& StreamedFile::stream() { return path_ == "-" ? std::cout : file_; }

void StreamedFile::commit() {
  stream().flush();
  if (!stream()) throw std::runtime_error("cannot write '" + path_ + "'");
  if (part_.empty()) return;
  file_.close();
  std::error_code error;
  std::filesystem::rename(part_, path_, error);
  if (error) throw std::runtime_error("cannot write '" + path_ + "': " + error.message());
  part_.clear();
}

void write_file(const std::string& path, const std::string& text) {
  StreamedFile out(path);
  out.stream() << text;
  out.commit();
}

}  // namespace endatsim::scenarios

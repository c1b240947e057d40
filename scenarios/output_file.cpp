#include "endatsim/scenarios/output_file.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "endatsim/scenarios/limits.hpp"

namespace endatsim::scenarios {
namespace fs = std::filesystem;

namespace {

std::string shown(const std::string& path) { return "'" + trimmed(path, 200) + "'"; }

// Writable by this process, and not marked read-only for everyone (which the superuser would
// otherwise write over).
bool writable(const std::string& path, const struct stat& st) {
  return (st.st_mode & 0222) != 0 && ::access(path.c_str(), S_ISDIR(st.st_mode) ? W_OK | X_OK : W_OK) == 0;
}

}  // namespace

FdBuffer::FdBuffer() {
  buffer_.resize(1 << 16);
  setp(buffer_.data(), buffer_.data() + buffer_.size());
}

bool FdBuffer::drain() {
  const char* p = pbase();
  std::size_t left = static_cast<std::size_t>(pptr() - pbase());
  while (left > 0 && error_ == 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      error_ = n < 0 ? errno : EIO;
      break;
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  setp(buffer_.data(), buffer_.data() + buffer_.size());
  return error_ == 0;
}

FdBuffer::int_type FdBuffer::overflow(int_type c) {
  if (!drain()) return traits_type::eof();
  if (!traits_type::eq_int_type(c, traits_type::eof())) {
    *pptr() = traits_type::to_char_type(c);
    pbump(1);
  }
  return traits_type::not_eof(c);
}

int FdBuffer::sync() { return drain() ? 0 : -1; }

StreamedFile::StreamedFile(const std::string& path) : path_(path) {
  if (path == "-") return;
  std::error_code status_error;
  const auto status = fs::status(path, status_error);
  const bool special = fs::exists(status) && !fs::is_regular_file(status);
  if (!special) part_ = path + ".part-" + std::to_string(::getpid());
  // A part file is created afresh (never through a link left in its place).
  fd_ = special ? ::open(path.c_str(), O_WRONLY | O_CLOEXEC)
                : ::open(part_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (fd_ < 0) {
    const int error = errno;
    part_.clear();
    fail(error);
  }
  buffer_.attach(fd_);
}

StreamedFile::~StreamedFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!part_.empty()) ::unlink(part_.c_str());
}

void StreamedFile::fail(int error) const {
  throw std::runtime_error("cannot write " + shown(path_) + ": " + (error != 0 ? std::strerror(error) : "write error"));
}

std::ostream& StreamedFile::stream() { return path_ == "-" ? std::cout : file_; }

void StreamedFile::commit() {
  stream().flush();
  if (path_ == "-") {  // the reason is kept by CheckedStdout, which the tools report at exit
    if (!std::cout) throw std::runtime_error("cannot write to standard output");
    return;
  }
  if (buffer_.error() != 0 || !file_) fail(buffer_.error());
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail(errno);
  if (part_.empty()) return;
  if (::rename(part_.c_str(), path_.c_str()) != 0) fail(errno);
  part_.clear();
}

void write_file(const std::string& path, const std::string& text) {
  StreamedFile out(path);
  out.stream() << text;
  out.commit();
}

void check_output_paths(const std::vector<std::string>& inputs, const std::string& inputs_are,
                        const std::vector<OutputPath>& outputs) {
  // The same file: the same device and inode when it exists, the same normalized path otherwise.
  const auto same = [](const std::string& a, const std::string& b) {
    struct stat sa {}, sb {};
    if (::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    std::error_code ea, eb;
    // From the absolute path: "x" and "./x" of a file yet to be made would differ otherwise.
    const auto ca = fs::weakly_canonical(fs::absolute(a), ea), cb = fs::weakly_canonical(fs::absolute(b), eb);
    return ea || eb ? a == b : ca == cb;
  };
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const auto& o = outputs[i];
    if (o.path == "-") {
      // Two outputs through one stream would interleave into something neither reader can parse.
      for (std::size_t j = 0; j < i; ++j)
        if (outputs[j].path == "-")
          throw std::runtime_error(outputs[j].option + " - and " + o.option +
                                   " -: only one output can go to standard output; give the other a file");
      if (o.directory)
        throw std::runtime_error(o.option + " -: several files cannot go to standard output; give a directory");
      continue;
    }
    const std::string what = o.option + " " + trimmed(o.path, 200) + ": ";
    const std::string cannot = what + "cannot open the file for writing: ";
    if (o.path.empty()) throw std::runtime_error(o.option + ": an empty path");
    struct stat st {};
    const bool exists = ::stat(o.path.c_str(), &st) == 0;
    if (exists && S_ISCHR(st.st_mode)) continue;  // /dev/null: written directly, every write checked
    for (const auto& input : inputs)
      if (same(input, o.path))
        throw std::runtime_error(what + "that is " + inputs_are + " (" + trimmed(input, 200) + "), which it would overwrite");
    for (std::size_t j = 0; j < i; ++j)
      if (outputs[j].path != "-" && same(outputs[j].path, o.path))
        throw std::runtime_error(outputs[j].option + " " + trimmed(outputs[j].path, 200) + " and " + what +
                                 "the same file (one would overwrite the other)");
    if (exists) {
      if (S_ISDIR(st.st_mode) && !o.directory) throw std::runtime_error(cannot + "it is a directory");
      if (S_ISFIFO(st.st_mode) || S_ISSOCK(st.st_mode) || S_ISBLK(st.st_mode))
        throw std::runtime_error(cannot + "it is a FIFO, socket or block device, not a file (- writes to standard output)");
      if (!writable(o.path, st)) throw std::runtime_error(cannot + (S_ISDIR(st.st_mode) ? "a read-only directory" : "it is read-only"));
      if (S_ISDIR(st.st_mode)) continue;
    } else if (o.directory) {
      continue;  // created when it is written
    }
    // The part file goes beside it: its directory must exist and be writable.
    fs::path parent = fs::path(o.path).parent_path();
    if (parent.empty()) parent = ".";
    struct stat pt {};
    if (::stat(parent.c_str(), &pt) != 0) throw std::runtime_error(cannot + "its directory " + shown(parent.string()) + " does not exist");
    if (!S_ISDIR(pt.st_mode)) throw std::runtime_error(cannot + shown(parent.string()) + " is not a directory");
    if (!writable(parent.string(), pt)) throw std::runtime_error(cannot + "its directory " + shown(parent.string()) + " is read-only");
  }
}

bool writes_to_stdout(const std::vector<OutputPath>& outputs) {
  return std::any_of(outputs.begin(), outputs.end(), [](const OutputPath& o) { return o.path == "-"; });
}

std::vector<std::string> remove_outputs(const std::vector<OutputPath>& outputs) {
  std::vector<std::string> removed;
  for (const auto& o : outputs) {
    if (o.path == "-" || o.directory) continue;
    struct stat st {};
    if (::lstat(o.path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) continue;
    if (::unlink(o.path.c_str()) == 0) removed.push_back(o.path);
  }
  return removed;
}

// Passes everything to standard output's own buffer and keeps the errno of the first failure.
class CheckedStdout::Watch : public std::streambuf {
 public:
  explicit Watch(std::streambuf* inner) : inner_(inner) {}
  int error() const { return error_; }

 protected:
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return sync() == 0 ? traits_type::not_eof(c) : c;
    errno = 0;
    const int_type r = inner_->sputc(traits_type::to_char_type(c));
    if (traits_type::eq_int_type(r, traits_type::eof())) failed();
    return r;
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    errno = 0;
    const std::streamsize written = inner_->sputn(s, n);
    if (written < n) failed();
    return written;
  }
  int sync() override {
    errno = 0;
    const int r = inner_->pubsync();
    if (r != 0 || std::fflush(stdout) != 0) {
      failed();
      return -1;
    }
    return 0;
  }

 private:
  void failed() {
    if (error_ == 0) error_ = errno != 0 ? errno : EIO;
  }
  std::streambuf* inner_;
  int error_ = 0;
};

CheckedStdout::CheckedStdout(std::string program)
    : program_(std::move(program)), watch_(std::make_unique<Watch>(std::cout.rdbuf())), previous_(std::cout.rdbuf(watch_.get())) {}

CheckedStdout::~CheckedStdout() { std::cout.rdbuf(previous_); }

int CheckedStdout::finish(int status) {
  std::cout.flush();
  std::cout.rdbuf(previous_);
  if (watch_->error() == 0 && std::ferror(stdout) == 0) return status;
  const int error = watch_->error() != 0 ? watch_->error() : EIO;
  std::cerr << program_ << ": cannot write to standard output: " << std::strerror(error) << std::endl;
  return status >= 2 ? status : 2;
}

}  // namespace endatsim::scenarios

#include "sim/vcd.hpp"

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

}  // namespace

VcdWriter::VcdWriter(Kernel& kernel, const std::string& path)
    : kernel_(kernel), file_(std::fopen(path.c_str(), "wb")), path_(path) {
  if (file_ == nullptr) throw std::runtime_error("cannot open VCD file '" + path + "' for writing");
  buffer_.reserve(1 << 16);
}

VcdWriter::~VcdWriter() {
  if (started_ && !finished_) finish();
  if (file_ != nullptr) std::fclose(file_);
}

void VcdWriter::add(Signal& signal, const std::string& scope, const std::string& name) {
  if (started_) throw std::logic_error("VcdWriter::add after start");
  const std::size_t index = probes_.size();
  probes_.push_back(Probe{this, index, &signal, scope, name, short_id(index), signal.read(), false});
  signal.on_change(Action{&VcdWriter::on_change, &probes_.back(), 0});
}

void VcdWriter::start() {
  buffer_ += "$version endatsim $end\n$timescale 1ps $end\n";
  std::map<std::string, std::vector<const Probe*>> scopes;
  for (const Probe& p : probes_) scopes[p.scope].push_back(&p);
  for (const auto& [scope, probes] : scopes) {
    buffer_ += "$scope module " + scope + " $end\n";
    for (const Probe* p : probes) buffer_ += "$var wire 1 " + p->id + " " + p->name + " $end\n";
    buffer_ += "$upscope $end\n";
  }
  buffer_ += "$enddefinitions $end\n#" + std::to_string(kernel_.now().count()) + "\n$dumpvars\n";
  stamped_ = kernel_.now();
  for (Probe& p : probes_) {
    p.written = p.signal->read();
    buffer_ += (p.written ? '1' : '0') + p.id + "\n";
  }
  buffer_ += "$end\n";
  kernel_.on_time_step_end(Action{&VcdWriter::on_step_end, this, 0});
  started_ = true;
}

void VcdWriter::on_change(void* probe, std::uint64_t) {
  auto& p = *static_cast<Probe*>(probe);
  VcdWriter* w = p.owner;
  if (!p.dirty && w->started_ && !w->finished_) {
    p.dirty = true;
    w->dirty_.push_back(p.index);
  }
}

void VcdWriter::on_step_end(void* self, std::uint64_t) {
  auto* w = static_cast<VcdWriter*>(self);
  if (w->dirty_.empty()) return;
  bool stamped = w->stamped_ == w->kernel_.now();
  for (std::size_t index : w->dirty_) {
    Probe& p = w->probes_[index];
    p.dirty = false;
    const bool v = p.signal->read();
    if (v == p.written) continue;  // changed and changed back within the step
    if (!stamped) {
      w->buffer_ += '#';
      w->buffer_ += std::to_string(w->kernel_.now().count());
      w->buffer_ += '\n';
      stamped = true;
      w->stamped_ = w->kernel_.now();
    }
    p.written = v;
    w->buffer_ += v ? '1' : '0';
    w->buffer_ += p.id;
    w->buffer_ += '\n';
  }
  w->dirty_.clear();
  w->flush_if_full();
}

void VcdWriter::flush_if_full() {
  if (buffer_.size() < (1 << 16) - 256) return;
  if (std::fwrite(buffer_.data(), 1, buffer_.size(), file_) != buffer_.size())
    throw std::runtime_error("write error on VCD file '" + path_ + "'");
  buffer_.clear();
}

void VcdWriter::finish() {
  if (finished_) return;
  finished_ = true;
  if (stamped_ != kernel_.now()) {
    buffer_ += '#';
    buffer_ += std::to_string(kernel_.now().count());
    buffer_ += '\n';
  }
  const bool ok = std::fwrite(buffer_.data(), 1, buffer_.size(), file_) == buffer_.size();
  buffer_.clear();
  if (std::fflush(file_) != 0 || !ok) throw std::runtime_error("write error on VCD file '" + path_ + "'");
}

}  // namespace endatsim::sim

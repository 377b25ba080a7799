// Atomic output files and exact number formatting.
#include "wb/output.h"

#include <unistd.h>
#include <charconv>
#include <cstring>
#include <stdexcept>

#include "wb/input.h"

namespace wb {

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  tmp_ = path_ + ".tmp-" + std::to_string(::getpid());
  f_ = std::fopen(tmp_.c_str(), "wb");
  if (!f_) {
    throw InputError(path_ + ": cannot open for writing (" + std::strerror(errno) + ")");
  }
}

AtomicFile::~AtomicFile() {
  if (f_) {
    std::fclose(f_);
    std::remove(tmp_.c_str());
  }
}

void AtomicFile::write(const char* s, std::size_t n) {
  if (std::fwrite(s, 1, n, f_) != n) {
    throw std::runtime_error(path_ + ": write failed (" + std::strerror(errno) + ")");
  }
}

void AtomicFile::commit() {
  bool ok = std::fflush(f_) == 0;
  ok = std::fclose(f_) == 0 && ok;
  f_ = nullptr;
  if (!ok || std::rename(tmp_.c_str(), path_.c_str()) != 0) {
    std::string why = std::strerror(errno);
    std::remove(tmp_.c_str());
    throw std::runtime_error(path_ + ": could not be written (" + why + ")");
  }
}

CsvFile::CsvFile(const std::string& path, const char* header) {
  if (!path.empty()) {
    file_.emplace(path);
    buf_ = header;
  }
}

void CsvFile::flush_if_large() {
  if (file_ && buf_.size() > (1u << 20)) {
    file_->write(buf_);
    buf_.clear();
  }
}

void CsvFile::commit() {
  if (file_) {
    file_->write(buf_);
    buf_.clear();
    file_->commit();
  }
}

void append_number(std::string& out, double x) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::general, 17);
  out.append(buf, r.ptr);
}

void append_int(std::string& out, long long x) {
  char buf[24];
  auto r = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, r.ptr);
}

}  // namespace wb

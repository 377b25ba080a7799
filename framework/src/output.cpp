// Atomic output files and exact number formatting.
#include "wb/output.h"

#include <unistd.h>

#include <charconv>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "wb/input.h"

namespace wb {

namespace {

// Temporary files not yet committed, removed by a signal that ends the
// process (SIGINT, SIGTERM, SIGHUP) before it dies: a stopped run leaves no
// "<path>.tmp-<pid>" behind. Fixed slots, since a handler may not allocate.
constexpr int kTmpSlots = 8;
constexpr std::size_t kTmpPathBytes = 4096;
char g_tmp[kTmpSlots][kTmpPathBytes];
volatile std::sig_atomic_t g_tmp_used[kTmpSlots];

extern "C" void remove_tmp_and_die(int sig) {
  for (int k = 0; k < kTmpSlots; ++k)
    if (g_tmp_used[k]) ::unlink(g_tmp[k]);
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

int register_tmp(const std::string& tmp) {
  static const bool installed = [] {
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
      if (std::signal(sig, remove_tmp_and_die) == SIG_IGN) std::signal(sig, SIG_IGN);
    }
    return true;
  }();
  (void)installed;
  if (tmp.size() >= kTmpPathBytes) return -1;
  for (int k = 0; k < kTmpSlots; ++k) {
    if (!g_tmp_used[k]) {
      std::memcpy(g_tmp[k], tmp.c_str(), tmp.size() + 1);
      g_tmp_used[k] = 1;
      return k;
    }
  }
  return -1;
}

void unregister_tmp(int slot) {
  if (slot >= 0) g_tmp_used[slot] = 0;
}

}  // namespace

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  // Only a regular file (or a new one) is replaced by the rename: a device, a
  // FIFO or a socket (/dev/null, a pipe) is written through, as a shell's
  // redirection would; a symbolic link's target is replaced, not the link.
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path_, ec);
  if (!ec && fs::exists(st) && !fs::is_regular_file(st) && !fs::is_directory(st)) {
    f_ = std::fopen(path_.c_str(), "wb");
    if (!f_) {
      throw InputError(path_ + ": cannot open for writing (" + std::strerror(errno) + ")");
    }
    return;
  }
  std::string target = path_;
  if (fs::is_symlink(fs::symlink_status(path_, ec))) {
    const fs::path real = fs::canonical(path_, ec);
    if (!ec) target = real.string();
  }
  target_ = target;
  tmp_ = target + ".tmp-" + std::to_string(::getpid());
  f_ = std::fopen(tmp_.c_str(), "wb");
  if (!f_) {
    throw InputError(path_ + ": cannot open for writing (" + std::strerror(errno) + ")");
  }
  slot_ = register_tmp(tmp_);
}

AtomicFile::~AtomicFile() {
  if (f_) {
    std::fclose(f_);
    if (!tmp_.empty()) std::remove(tmp_.c_str());
  }
  unregister_tmp(slot_);
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
  if (tmp_.empty()) {  // written through
    if (!ok)
      throw std::runtime_error(path_ + ": could not be written (" + std::strerror(errno) + ")");
    return;
  }
  if (!ok || std::rename(tmp_.c_str(), target_.c_str()) != 0) {
    std::string why = std::strerror(errno);
    std::remove(tmp_.c_str());
    unregister_tmp(slot_);
    slot_ = -1;
    throw std::runtime_error(path_ + ": could not be written (" + why + ")");
  }
  unregister_tmp(slot_);
  slot_ = -1;
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

// Output files that never leave a half-written file over a good one, and
// numbers printed so that they read back exactly.
#pragma once
#include <cstdio>
#include <optional>
#include <string>

namespace wb {

// Writes to "<path>.tmp-<pid>" and renames over <path> on commit(); a file
// destroyed before commit() (an error, a crash unwinding) or a run stopped by
// SIGINT, SIGTERM or SIGHUP removes its temporary. Only a regular file (or a
// new one) is replaced: a path that is a device or a FIFO (/dev/null, a pipe)
// is written through, and a symbolic link's target is replaced, not the link.
class AtomicFile {
 public:
  explicit AtomicFile(std::string path);  // throws InputError naming the path
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  std::FILE* get() { return f_; }
  void write(const char* s, std::size_t n);
  void write(const std::string& s) { write(s.data(), s.size()); }
  void commit();  // throws std::runtime_error if the data could not be written

 private:
  std::string path_, target_, tmp_;  // tmp_ empty: written through
  std::FILE* f_ = nullptr;
  int slot_ = -1;  // in the table of temporaries a signal removes
};

// A CSV output, or nothing when its path is empty: opened (and so checked) at
// once, its rows appended to rows(), written a megabyte at a time by
// flush_if_large() and moved into place by commit().
class CsvFile {
 public:
  CsvFile(const std::string& path, const char* header);  // throws InputError naming the path
  explicit operator bool() const { return file_.has_value(); }
  std::string& rows() { return buf_; }
  void flush_if_large();
  void commit();

 private:
  std::optional<AtomicFile> file_;
  std::string buf_;
};

// Appends x with 17 significant digits (reads back to the same double).
void append_number(std::string& out, double x);
// Appends a whole number.
void append_int(std::string& out, long long x);

}  // namespace wb

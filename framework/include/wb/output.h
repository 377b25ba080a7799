// Output files that never leave a half-written file over a good one, and
// numbers printed so that they read back exactly.
#pragma once
#include <cstdio>
#include <string>

namespace wb {

// Writes to "<path>.tmp-<pid>" and renames over <path> on commit(); a file
// destroyed before commit() (an error, a crash unwinding) removes its temporary.
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
  std::string path_, tmp_;
  std::FILE* f_ = nullptr;
};

// Appends x with 17 significant digits (reads back to the same double).
void append_number(std::string& out, double x);
// Appends a whole number.
void append_int(std::string& out, long long x);

}  // namespace wb

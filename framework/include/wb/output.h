// Output files that never leave a half-written file over a good one, and
// numbers printed so that they read back exactly. Every output of every lab
// goes through here: its path is checked before the run (check_output_path),
// and a file that cannot be opened or written is bad input (InputError, exit
// status 2, one line naming the flag and the file), never an internal error.
#pragma once
#include <cstdio>
#include <optional>
#include <string>

namespace wb {

// Writes to "<path>.tmp-<pid>" and renames over <path> on commit(); a file
// destroyed before commit() (an error, a crash unwinding), a run stopped by any
// catchable signal (SIGINT, SIGTERM, SIGXCPU, ...) or by its budget (wb/budget.h)
// removes its temporary, and the next AtomicFile in that folder removes one that a
// killed run left (remove_stale_temporaries). The file replaced keeps its permissions. Only a
// regular file (or a new one) is replaced: a path that is a device or a FIFO (/dev/null, a pipe)
// is written through, and a symbolic link's target is replaced, not the link.
//
// The temporary is "<name>.tmp-<pid>" beside the file, its name cut (at a
// character boundary) when the whole would pass the file system's NAME_MAX.
class AtomicFile {
 public:
  // `flag` names the output in messages ("--out"). Throws InputError.
  explicit AtomicFile(std::string path, std::string flag = "");
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  std::FILE* get() { return f_; }
  void write(const char* s, std::size_t n);
  void write(const std::string& s) { write(s.data(), s.size()); }
  void commit();  // throws InputError if the data could not be written
  // Written through (a device, a FIFO), not to a temporary?
  bool through() const { return tmp_.empty(); }

 private:
  [[noreturn]] void fail(const char* what, int err);
  std::string path_, flag_, target_, tmp_;  // tmp_ empty: written through
  std::FILE* f_ = nullptr;
  int slot_ = -1;  // in the table of temporaries a signal removes
};

// A CSV output, or nothing when its path is empty: opened (and so checked) at
// once, its rows appended to rows(), written a megabyte at a time by
// flush_if_large() and moved into place by commit().
// A file written through (a device) gets its header at once, so that one that
// cannot be written (/dev/full) is refused before the run starts.
class CsvFile {
 public:
  CsvFile() = default;  // nothing
  // Throws InputError naming `flag` and the path.
  CsvFile(const std::string& path, const std::string& header, const std::string& flag = "");
  explicit operator bool() const { return file_.has_value(); }
  std::string& rows() { return buf_; }
  void flush_if_large();
  void commit();

 private:
  std::optional<AtomicFile> file_;
  std::string buf_;
};

// Checks before a run that `path` can be an output (AtomicFile): not empty, not
// a folder, in an existing folder that can be written, a file name of at most
// NAME_MAX bytes and a path of at most PATH_MAX; an existing device or FIFO must
// be writable. Throws InputError naming `flag`.
void check_output_path(const std::string& flag, const std::string& path);

// Two files given the same path (or two names of one file) would mix their rows
// or overwrite the input: refused, unless the file is a character device
// (writing both to /dev/null is fine). Either may be empty (not given).
void check_distinct(const std::string& flag_a, const std::string& a, const std::string& flag_b,
                    const std::string& b);

// Removes every temporary of this process not yet committed (async-signal-safe): the
// budget's stop (wb/budget.h) and the signal handlers call it before the process ends.
void remove_temporaries();

// Removes from `dir` the temporaries ("<name>.tmp-<pid>") that runs killed without a
// chance to clean up (SIGKILL) left: their process is gone, no one holds their lock,
// they are the user's own regular files and hold what a CsvFile writes (or nothing).
// Every AtomicFile calls it for its folder before it creates its own.
void remove_stale_temporaries(const std::string& dir);

// Appends x with 17 significant digits (reads back to the same double).
void append_number(std::string& out, double x);
// Appends a whole number.
void append_int(std::string& out, long long x);

}  // namespace wb

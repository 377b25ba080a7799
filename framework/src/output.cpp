// Atomic output files and exact number formatting.
#include "wb/output.h"

#include <dirent.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <charconv>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "wb/input.h"

namespace wb {

namespace {

// Temporary files not yet committed, removed by every catchable signal that ends the
// process before it dies (SIGINT, SIGTERM, SIGXCPU, SIGSEGV, ...; list below), and by
// the budget's stop (wb/budget.h): a stopped run leaves no "<path>.tmp-<pid>" behind.
// Fixed slots, since a handler may not allocate. (SIGKILL cannot be caught: the next
// run writing in that folder removes what a killed one left, remove_stale_temporaries.)
constexpr int kTmpSlots = 8;
constexpr std::size_t kTmpPathBytes = 4096;
char g_tmp[kTmpSlots][kTmpPathBytes];
volatile std::sig_atomic_t g_tmp_used[kTmpSlots];

// What each signal did before: a handler that was there (a sanitizer's, libFuzzer's)
// still runs after the temporaries are gone.
struct sigaction g_previous[NSIG];

extern "C" void remove_tmp_and_die(int sig, siginfo_t* info, void* context) {
  remove_temporaries();
  const struct sigaction& prev = g_previous[sig];
  if ((prev.sa_flags & SA_SIGINFO) && prev.sa_sigaction) {
    prev.sa_sigaction(sig, info, context);
    return;
  }
  if (prev.sa_handler != SIG_DFL && prev.sa_handler != SIG_IGN && prev.sa_handler) {
    prev.sa_handler(sig);
    return;
  }
  // The default action: die of the signal (a fault raised again by the instruction
  // that caused it, once this handler returns).
  ::sigaction(sig, &prev, nullptr);
  std::raise(sig);
}

// Every signal whose default action ends the process and that a handler can catch.
// SIGPROF is the budget's ticker when it runs (its stop removes the temporaries).
void install_signal_handlers() {
  std::vector<int> sigs = {SIGHUP,  SIGINT,  SIGQUIT,   SIGILL,  SIGTRAP, SIGABRT, SIGBUS,
                           SIGFPE,  SIGUSR1, SIGSEGV,   SIGUSR2, SIGPIPE, SIGALRM, SIGTERM,
                           SIGXCPU, SIGXFSZ, SIGVTALRM, SIGSYS,  SIGPROF};
#ifdef SIGSTKFLT
  sigs.push_back(SIGSTKFLT);
#endif
#ifdef SIGPWR
  sigs.push_back(SIGPWR);
#endif
#ifdef SIGIO
  sigs.push_back(SIGIO);
#endif
#ifdef SIGRTMIN
  for (int s = SIGRTMIN; s <= SIGRTMAX; ++s) sigs.push_back(s);
#endif
  for (int sig : sigs) {
    struct sigaction old {};
    if (sig <= 0 || sig >= NSIG || ::sigaction(sig, nullptr, &old) != 0) continue;
    if (old.sa_handler == SIG_IGN) continue;                    // ignored stays ignored (nohup)
    if (sig == SIGPROF && old.sa_handler != SIG_DFL) continue;  // the budget's ticker
    g_previous[sig] = old;
    struct sigaction sa {};
    sa.sa_sigaction = remove_tmp_and_die;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_SIGINFO | SA_RESTART;
    ::sigaction(sig, &sa, nullptr);
  }
}

int register_tmp(const std::string& tmp) {
  static const bool installed = [] {
    install_signal_handlers();
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

void remove_temporaries() {
  for (int k = 0; k < kTmpSlots; ++k)
    if (g_tmp_used[k]) ::unlink(g_tmp[k]);
}

namespace {

namespace fs = std::filesystem;

// The longest file name the folder of `p` takes (NAME_MAX, 255 on Linux).
std::size_t name_max(const fs::path& p) {
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  const long n = ::pathconf(dir.c_str(), _PC_NAME_MAX);
  return n > 0 ? std::size_t(n) : 255;
}

// The longest prefix of `s` of at most `max` bytes that does not cut a UTF-8 sequence.
std::string cut_utf8(const std::string& s, std::size_t max) {
  if (s.size() <= max) return s;
  std::size_t k = max;
  while (k > 0 && (static_cast<unsigned char>(s[k]) & 0xC0) == 0x80) --k;
  return s.substr(0, k);
}

std::string label(const std::string& flag, const std::string& path) {
  return (flag.empty() ? "" : flag + ": ") + path;
}

// The file a write to `path` replaces: symbolic links followed (a dangling one
// to the file it names), the rest made absolute and normal.
fs::path output_target(const std::string& path) {
  std::error_code ec;
  fs::path p(path);
  for (int hops = 0; hops < 40 && fs::is_symlink(fs::symlink_status(p, ec)); ++hops) {
    const fs::path to = fs::read_symlink(p, ec);
    if (ec) break;
    p = to.is_absolute() ? to : p.parent_path() / to;
  }
  const fs::path w = fs::weakly_canonical(p, ec);
  return ec ? p : w;
}

// The first bytes of every file a CsvFile writes (the traces, stats and sweep tables of
// docs/run-contract.md): a temporary that begins otherwise is not one of ours.
bool ours(const char* head, std::size_t n) {
  if (n == 0) return true;  // killed before its first flush
  for (const char* h : {"t,id,", "step,t,", "scene,integrator,"}) {
    const std::size_t k = std::strlen(h);
    if (n >= k && std::memcmp(head, h, k) == 0) return true;
  }
  return false;
}

}  // namespace

void remove_stale_temporaries(const std::string& dir) {
  DIR* d = ::opendir(dir.c_str());
  if (!d) return;
  const std::string me = std::to_string(::getpid());
  while (const dirent* e = ::readdir(d)) {
    // "<name>.tmp-<pid>": the pid all digits, not ours, and not alive.
    const std::string name = e->d_name;
    const auto dot = name.rfind(".tmp-");
    if (dot == std::string::npos || dot == 0) continue;
    const std::string pid = name.substr(dot + 5);
    if (pid.empty() || pid.size() > 9 || pid == me ||
        pid.find_first_not_of("0123456789") != std::string::npos) {
      continue;
    }
    if (::kill(pid_t(std::stol(pid)), 0) == 0 || errno != ESRCH)
      continue;  // alive (or not ours to ask)
    const std::string path = dir + "/" + name;
    const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) continue;
    struct stat st {};
    char head[32];
    bool stale =
        ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_uid == ::geteuid() &&
        ::flock(fd, LOCK_EX | LOCK_NB) == 0;  // no writer holds it (another pid namespace)
    if (stale) {
      const ssize_t n = ::read(fd, head, sizeof head);
      stale = n >= 0 && ours(head, std::size_t(n));
    }
    if (stale) ::unlink(path.c_str());
    ::close(fd);
  }
  ::closedir(d);
}

void check_output_path(const std::string& flag, const std::string& path) {
  std::error_code ec;
  const fs::path p(path);
  if (path.empty()) throw InputError(flag + ": got an empty path, expected a file name");
  if (path.size() > std::size_t(PATH_MAX) - 32) {
    throw InputError(flag + ": got a path of " + std::to_string(path.size()) +
                     " bytes, expected at most " + std::to_string(PATH_MAX - 32) +
                     " (the system's PATH_MAX, less room for the temporary's suffix)");
  }
  if (fs::is_directory(p, ec)) {
    throw InputError(flag + ": got \"" + path + "\", a folder, expected a file name");
  }
  const fs::file_status st = fs::status(p, ec);
  if (!ec && fs::exists(st) && !fs::is_regular_file(st)) {  // /dev/null, a FIFO: written through
    if (::access(path.c_str(), W_OK) != 0) {
      throw InputError(flag + ": got \"" + path + "\", expected a file you can write");
    }
    return;
  }
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  if (!fs::is_directory(dir, ec)) {
    throw InputError(flag + ": got \"" + path + "\", expected a file in an existing folder (\"" +
                     dir.string() + "\" does not exist)");
  }
  if (::access(dir.c_str(), W_OK) != 0) {
    throw InputError(flag + ": got \"" + path +
                     "\", expected a file in a folder you can write (\"" + dir.string() +
                     "\" is not writable)");
  }
  // An existing file the user may not write is refused, as a shell's redirection would
  // refuse it: the rename could replace it (the folder is writable), but it is not ours to.
  if (!ec && fs::exists(st) && ::access(path.c_str(), W_OK) != 0) {
    throw InputError(flag + ": got \"" + path +
                     "\", a file you may not write (its permissions do not let you), expected "
                     "a file you can write or a new one");
  }
  const std::string name = p.filename().string();
  if (name.size() > name_max(p)) {
    throw InputError(flag + ": got a file name of " + std::to_string(name.size()) +
                     " bytes, expected at most " + std::to_string(name_max(p)) +
                     " (the file system's NAME_MAX)");
  }
}

void check_distinct(const std::string& flag_a, const std::string& a, const std::string& flag_b,
                    const std::string& b) {
  if (a.empty() || b.empty()) return;
  std::error_code ec;
  // Two names of one existing file (a hard link), or of the file a write replaces.
  bool same = fs::equivalent(a, b, ec);
  if (ec) same = a == b || output_target(a) == output_target(b);
  if (same && !fs::is_character_file(a, ec)) {
    throw InputError(flag_a + " and " + flag_b + ": both got \"" + a + "\"" +
                     (a == b ? "" : " and \"" + b + "\" (one file)") +
                     ", expected two different files");
  }
}

AtomicFile::AtomicFile(std::string path, std::string flag)
    : path_(std::move(path)), flag_(std::move(flag)) {
  // Only a regular file (or a new one) is replaced by the rename: a device, a
  // FIFO or a socket (/dev/null, a pipe) is written through, as a shell's
  // redirection would; a symbolic link's target is replaced, not the link.
  std::error_code ec;
  const fs::file_status st = fs::status(path_, ec);
  if (!ec && fs::exists(st) && !fs::is_regular_file(st) && !fs::is_directory(st)) {
    f_ = std::fopen(path_.c_str(), "wb");
    if (!f_) fail("cannot open for writing", errno);
    return;
  }
  std::string target = path_;
  if (fs::is_symlink(fs::symlink_status(path_, ec))) target = output_target(path_).string();
  target_ = target;
  // "<name>.tmp-<pid>", the name cut so that the whole fits NAME_MAX.
  const fs::path t(target);
  const std::string suffix = ".tmp-" + std::to_string(::getpid());
  const std::size_t max = name_max(t);
  const std::string name =
      cut_utf8(t.filename().string(), max > suffix.size() ? max - suffix.size() : 1);
  tmp_ = (t.has_parent_path() ? (t.parent_path() / (name + suffix)) : fs::path(name + suffix))
             .string();
  // What a run killed in this folder (SIGKILL: no handler runs) left behind goes first.
  remove_stale_temporaries(t.has_parent_path() ? t.parent_path().string() : ".");
  f_ = std::fopen(tmp_.c_str(), "wb");
  if (!f_) {
    const int err = errno;
    tmp_.clear();
    fail("cannot open for writing", err);
  }
  slot_ = register_tmp(tmp_);
  // Held until the file is closed, or the process ends however it ends: a later run
  // that can take the lock knows the writer is gone (remove_stale_temporaries).
  ::flock(::fileno(f_), LOCK_EX | LOCK_NB);
}

AtomicFile::~AtomicFile() {
  if (f_) {
    std::fclose(f_);
    if (!tmp_.empty()) std::remove(tmp_.c_str());
  }
  unregister_tmp(slot_);
}

void AtomicFile::fail(const char* what, int err) {
  throw InputError(label(flag_, path_) + ": " + what + " (" + std::strerror(err) + ")");
}

void AtomicFile::write(const char* s, std::size_t n) {
  if (std::fwrite(s, 1, n, f_) != n) fail("could not be written", errno);
}

void AtomicFile::commit() {
  // The file replaced keeps its permissions (and its owner, where we may set it), as a
  // shell's redirection into it would: a 0600 file does not become 0644.
  struct stat old {};
  if (!tmp_.empty() && ::stat(target_.c_str(), &old) == 0 && S_ISREG(old.st_mode)) {
    const int fd = ::fileno(f_);
    ::fchmod(fd, old.st_mode & 07777);
    if (::fchown(fd, old.st_uid, old.st_gid) != 0) {
      // Not ours to give away: the new file is the writer's, its mode still the old one.
    }
  }
  bool ok = std::fflush(f_) == 0;
  int err = errno;
  if (std::fclose(f_) != 0 && ok) ok = false, err = errno;
  f_ = nullptr;
  if (tmp_.empty()) {  // written through
    if (!ok) fail("could not be written", err);
    return;
  }
  if (ok && std::rename(tmp_.c_str(), target_.c_str()) != 0) ok = false, err = errno;
  if (!ok) {
    std::remove(tmp_.c_str());
    unregister_tmp(slot_);
    slot_ = -1;
    fail("could not be written", err);
  }
  unregister_tmp(slot_);
  slot_ = -1;
}

CsvFile::CsvFile(const std::string& path, const std::string& header, const std::string& flag) {
  if (path.empty()) return;
  file_.emplace(path, flag);
  buf_ = header;
  if (file_->through()) {  // a device: the header now, so a failing one fails before the run
    file_->write(buf_);
    buf_.clear();
    if (std::fflush(file_->get()) != 0) {
      throw InputError(label(flag, path) + ": could not be written (" + std::strerror(errno) +
                       ")");
    }
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
#ifdef __cpp_lib_to_chars
  auto r = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::general, 17);
  out.append(buf, r.ptr);
#else
  // A library without to_chars for double (emscripten's libc++ 13, the live pages'
  // build: docs/live.md): printf's %.17g is what to_chars(general, 17) is defined as.
  const int n = std::snprintf(buf, sizeof buf, "%.17g", x);
  out.append(buf, std::size_t(n));
#endif
}

void append_int(std::string& out, long long x) {
  char buf[24];
  auto r = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, r.ptr);
}

}  // namespace wb

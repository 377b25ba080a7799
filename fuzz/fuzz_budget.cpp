// libFuzzer target: any bytes as a run of a lab executable, measured from outside
// (fuzz/README.md, "fuzz_budget"). The input's first line picks the lab and the mode
// ("collisions", "euler sweep", "forces out": a run with a trace), the rest is the scene
// file. The optimised executable (build/bin/<lab>-solution, or $WB_FUZZ_BUDGET_BIN) runs
// it with a small budget (--max-time kMaxTime --max-memory kMaxMib), and its CPU time and
// peak resident size are read from wait4.
// A finding is a run that passes either limit by more than 10 % (issue 45: whatever the
// cost model missed, the budget measured while running stops it), an exit status other
// than 0 (ran) or 2 (refused, or stopped), a stderr that is not lines of valid UTF-8 of at
// most 1100 bytes, or a temporary file left behind by a run that wrote a trace.
#include <dirent.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_checks.h"

extern char** environ;

namespace {

constexpr const char* kFuzzTarget = "fuzz_budget";
// The budget every run gets: small, so that a run the cost model underestimates meets
// its wall within the fuzzer's time, and above what a process needs to start.
constexpr double kMaxTime = 0.4;  // s of CPU
constexpr double kMaxMib = 300;
constexpr double kSlack = 1.1;  // issue 45: "exceeds its limit by more than 10 %"
const char* const kLabs[] = {"forces", "euler", "midpoint", "implicit", "collisions", "rigid"};

[[noreturn]] void finding(const char* what, const std::string& detail) {
  fuzzcheck::finding(kFuzzTarget, what, detail);
}

std::string bin_dir() {
  const char* env = std::getenv("WB_FUZZ_BUDGET_BIN");
  return env && *env ? env : WB_FUZZ_BUDGET_BIN;
}

const std::string& work_dir() {
  static const std::string dir = [] {
    char tmpl[] = "/tmp/wb-fuzz-budget-XXXXXX";
    const char* d = ::mkdtemp(tmpl);
    if (!d) finding("cannot make a temporary folder", "/tmp");
    return std::string(d);
  }();
  return dir;
}

std::vector<std::string> files_in(const std::string& dir) {
  std::vector<std::string> out;
  if (DIR* d = ::opendir(dir.c_str())) {
    while (const dirent* e = ::readdir(d)) {
      const std::string n = e->d_name;
      if (n != "." && n != "..") out.push_back(n);
    }
    ::closedir(d);
  }
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::size_t nl = text.find('\n');
  const std::string head = nl == std::string::npos ? "" : text.substr(0, nl);
  const std::string scene_text = nl == std::string::npos ? text : text.substr(nl + 1);
  // The lab the first line names, else one by the input's first byte.
  std::string lab = kLabs[size > 0 ? data[0] % 6 : 0];
  for (const char* l : kLabs) {
    if (head.rfind(l, 0) == 0) lab = l;
  }
  const bool sweep =
      head.find("sweep") != std::string::npos && lab != "forces" && lab != "collisions";
  const bool out = head.find("out") != std::string::npos;

  const std::string dir = work_dir(), scene = dir + "/scene.json", runs = dir + "/out";
  {
    std::ofstream f(scene, std::ios::binary | std::ios::trunc);
    f << scene_text;
  }
  std::system(("rm -rf '" + runs + "' && mkdir '" + runs + "'").c_str());
  char max_time[32], max_mib[32];
  std::snprintf(max_time, sizeof max_time, "%g", kMaxTime);
  std::snprintf(max_mib, sizeof max_mib, "%g", kMaxMib);
  const std::string exe = bin_dir() + "/" + lab + "-solution";
  std::vector<std::string> args = {exe,      "--scene",      scene,  "--max-time",
                                   max_time, "--max-memory", max_mib};
  if (sweep) args.insert(args.end(), {"--sweep", runs + "/sweep.csv", "--repeats", "1"});
  if (out && !sweep) args.insert(args.end(), {"--out", runs + "/trace.csv"});
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  const std::string err_path = dir + "/stderr";
  posix_spawn_file_actions_addopen(&fa, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, exe.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) finding("cannot run the lab executable (build it first)", exe);
  int status = 0;
  rusage ru{};
  while (::wait4(pid, &status, 0, &ru) < 0) {
  }

  const double cpu = double(ru.ru_utime.tv_sec) + 1e-6 * double(ru.ru_utime.tv_usec) +
                     double(ru.ru_stime.tv_sec) + 1e-6 * double(ru.ru_stime.tv_usec);
  const double mib = double(ru.ru_maxrss) / 1024.0;
  std::ifstream ef(err_path, std::ios::binary);
  std::stringstream es;
  es << ef.rdbuf();
  const std::string err = es.str();
  const std::string what = lab + (sweep ? " sweep" : "") + ": " + err.substr(0, 400);
  if (cpu > kSlack * kMaxTime) {
    finding("a run passed its --max-time by more than 10 %",
            std::to_string(cpu) + " s of CPU; " + what);
  }
  if (mib > kSlack * kMaxMib) {
    finding("a run passed its --max-memory by more than 10 %",
            std::to_string(mib) + " MiB; " + what);
  }
  if (!WIFEXITED(status) || (WEXITSTATUS(status) != 0 && WEXITSTATUS(status) != 2)) {
    finding("a run ended otherwise than with status 0 or 2",
            (WIFEXITED(status) ? "status " + std::to_string(WEXITSTATUS(status))
                               : "signal " + std::to_string(WTERMSIG(status))) +
                "; " + what);
  }
  std::size_t start = 0;
  while (start < err.size()) {
    const std::size_t end = err.find('\n', start);
    const std::string line = err.substr(start, end == std::string::npos ? end : end - start);
    fuzzcheck::check_message(kFuzzTarget, line, 1100);
    if (end == std::string::npos) break;
    start = end + 1;
  }
  for (const std::string& f : files_in(runs)) {
    if (f.find(".tmp-") != std::string::npos) finding("a temporary file was left behind", f);
  }
  return 0;
}

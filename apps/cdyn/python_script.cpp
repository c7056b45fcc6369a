// python_script.cpp — spawning python3 on an embedded script (see python_script.hpp).
#include "python_script.hpp"

#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>

#include "interrupt.hpp"

extern char** environ;

namespace cdyn::app {

namespace {

// The scripts' "no matplotlib here" exit status (scripts/plot_run.py, plot_study.py),
// and their status on Ctrl-C (they exit quietly with it, as the shell does).
constexpr int kNoMatplotlib = 3;
constexpr int kInterrupted = 130;

// Exit status of `interpreter -c script args...`, or -1 if it could not be started.
int spawn_and_wait(const std::string& interpreter, const char* script, const std::vector<std::string>& args) {
  std::vector<std::string> words = {interpreter, "-c", script};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  pid_t pid;
  if (posix_spawnp(&pid, interpreter.c_str(), nullptr, nullptr, argv.data(), environ) != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  if (WIFSIGNALED(status) && (WTERMSIG(status) == SIGINT || WTERMSIG(status) == SIGTERM)) return kInterrupted;
  if (!WIFEXITED(status)) return -1;
  const int code = WEXITSTATUS(status);
  return code == 127 ? -1 : code;  // 127: the exec itself failed
}

}  // namespace

std::string run_python_script(const char* script, const std::vector<std::string>& args) {
  std::vector<std::string> candidates = {"python3", "/usr/bin/python3"};
  if (const char* chosen = std::getenv("CDYN_PYTHON"); chosen && *chosen) candidates = {chosen};
  bool found_python = false;
  for (const std::string& python : candidates) {
    const int code = spawn_and_wait(python, script, args);
    if (code == 0) return "";
    // Ctrl-C reaches the script too (the terminal signals the whole process group):
    // no other interpreter is tried, the caller sees interrupted() and says so.
    if (code == kInterrupted || interrupted()) return "interrupted";
    if (code == -1) continue;
    found_python = true;
    if (code != kNoMatplotlib) return python + " failed on the plot script (exit status " + std::to_string(code) + ")";
  }
  return found_python ? "python3 has no matplotlib (install python3-matplotlib)" : "no python3 found";
}

}  // namespace cdyn::app

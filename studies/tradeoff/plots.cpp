// Spawning python3 on the plot script (posix_spawnp: no shell, so paths need no quoting).
#include "plots.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <vector>

extern char** environ;

namespace adb::tradeoff {

#ifndef ADB_TRADEOFF_PLOT_SCRIPT
#define ADB_TRADEOFF_PLOT_SCRIPT "studies/tradeoff/plot_tradeoff.py"
#endif

std::string plotScriptPath() { return ADB_TRADEOFF_PLOT_SCRIPT; }

bool runPlotScript(const std::string& outDir) {
  return runPythonScript(plotScriptPath(), outDir, "adb-tradeoff");
}

bool runPythonScript(const std::string& script, const std::string& outDir, const char* tool) {
  if (!std::ifstream(script)) {
    std::fprintf(stderr, "%s: warning: no plots: %s not found (the CSVs are written)\n", tool,
                 script.c_str());
    return false;
  }
  std::string python = "python3";
  std::vector<char*> argv{python.data(), const_cast<char*>(script.c_str()),
                          const_cast<char*>(outDir.c_str()), nullptr};
  pid_t pid = 0;
  const int spawnError = posix_spawnp(&pid, "python3", nullptr, nullptr, argv.data(), environ);
  if (spawnError != 0) {
    std::fprintf(stderr, "%s: warning: no plots: cannot run python3: %s\n", tool,
                 std::strerror(spawnError));
    return false;
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) break;
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::fprintf(stderr,
                 "%s: warning: the plot script failed (python3 and matplotlib "
                 "installed?); the CSVs in %s are the result\n",
                 tool, outDir.c_str());
    return false;
  }
  return true;
}

}  // namespace adb::tradeoff

// The machine line: /proc/cpuinfo's model name, hardware threads, compiler, assertions.
#include "machine_note.h"

#include <fstream>
#include <thread>

namespace adb::tradeoff {
namespace {

std::string cpuModel() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) == 0) {
      const std::size_t colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(' ', colon + 1));
    }
  }
  return "unknown CPU";
}

}  // namespace

std::string machineNote() {
  std::string note = cpuModel() + ", " + std::to_string(std::thread::hardware_concurrency()) +
                     " hardware threads (shared with whatever else ran), ";
#if defined(__clang__)
  note += "clang " __clang_version__;
#elif defined(__GNUC__)
  note += "GCC " __VERSION__;
#endif
#ifdef NDEBUG
  note += ", optimised build";
#else
  note += ", build with assertions (times are not representative)";
#endif
  return note;
}

}  // namespace adb::tradeoff

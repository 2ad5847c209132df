// The warning hook: one atomic function pointer, stderr by default.
#include "adb/bullet/warnings.h"

#include <atomic>
#include <cstdio>

namespace adb {
namespace {

void writeToStderr(const char* message) { std::fprintf(stderr, "adb warning: %s\n", message); }

std::atomic<WarningHandler> g_handler{&writeToStderr};

}  // namespace

WarningHandler setWarningHandler(WarningHandler handler) noexcept {
  return g_handler.exchange(handler ? handler : &writeToStderr);
}

void warn(const std::string& message) { g_handler.load()(message.c_str()); }

}  // namespace adb

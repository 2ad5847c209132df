// The warning hook of adb::bullet: conditions that are legal but probably a mistake (a body
// whose shape frame is not its principal frame, say) go to one replaceable handler, so an
// application can route them to its own log or turn them into test failures.
#pragma once

#include <string>

#include "adb/bullet/precision.h"

namespace adb {

/// Receives one warning, a full sentence without a trailing newline. May be called from any
/// thread that uses adb's shapes; the handler must be thread-safe if the application is.
using WarningHandler = void (*)(const char* message);

/// Installs `handler` for every later warning and returns the one it replaces. nullptr
/// restores the default, which writes "adb warning: <message>" and a newline to stderr.
/// Thread-safe (the handler is swapped atomically).
WarningHandler setWarningHandler(WarningHandler handler) noexcept;

/// Sends `message` to the current handler.
void warn(const std::string& message);

}  // namespace adb

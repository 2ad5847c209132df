// AssimpLogCapture: a LogStream on assimp's DefaultLogger, under one process-wide mutex.
#include "assimp_log_capture.h"

#include <assimp/DefaultLogger.hpp>
#include <assimp/LogStream.hpp>
#include <assimp/Logger.hpp>

#include "adb/io/message_text.h"

namespace adb::io::detail {
namespace {

constexpr unsigned kCapturedSeverities = Assimp::Logger::Warn | Assimp::Logger::Err;
// A damaged file can make assimp warn once per face: keep the first lines and count the rest.
constexpr std::size_t kMaxLines = 100;

std::mutex& loggerMutex() {
  static std::mutex mutex;
  return mutex;
}

// DefaultLogger formats a line as "Error, T0: <message>\n" ("Warn,  T0: ..." for warnings;
// T0 is assimp's thread id). Keep the message and name the severity; anything else is kept
// as it came, without the trailing newline.
std::string tidy(const char* raw) {
  std::string line(raw);
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
  const std::size_t comma = line.find(',');
  const std::size_t colon = line.find(": ");
  if (comma == std::string::npos || colon == std::string::npos || colon < comma) {
    return "assimp: " + excerpt(line);
  }
  const std::string severity = line.substr(0, comma);
  const std::string message = excerpt(std::string_view(line).substr(colon + 2));
  if (severity == "Error") return "assimp error: " + message;
  if (severity == "Warn") return "assimp warning: " + message;
  return "assimp " + severity + ": " + message;
}

}  // namespace

class AssimpLogCapture::Stream : public Assimp::LogStream {
 public:
  void write(const char* message) override {
    if (lines.size() < kMaxLines) {
      lines.push_back(tidy(message));
    } else {
      ++dropped;
    }
  }
  std::vector<std::string> lines;
  std::size_t dropped = 0;
};

AssimpLogCapture::AssimpLogCapture()
    : m_lock(loggerMutex()), m_stream(std::make_unique<Stream>()) {
  if (Assimp::DefaultLogger::isNullLogger()) {
    // No default streams (0): nothing goes to stdout or a file, only to our stream.
    Assimp::DefaultLogger::create("", Assimp::Logger::NORMAL, 0);
    m_ownsLogger = true;
  }
  Assimp::DefaultLogger::get()->attachStream(m_stream.get(), kCapturedSeverities);
}

AssimpLogCapture::~AssimpLogCapture() {
  // detachStream hands the stream back (it does not delete it); m_stream owns it.
  Assimp::DefaultLogger::get()->detachStream(m_stream.get(), kCapturedSeverities);
  if (m_ownsLogger) Assimp::DefaultLogger::kill();
}

std::vector<std::string> AssimpLogCapture::take() {
  std::vector<std::string> lines;
  lines.swap(m_stream->lines);
  if (m_stream->dropped > 0) {
    lines.push_back("assimp: " + std::to_string(m_stream->dropped) + " more messages not kept");
    m_stream->dropped = 0;
  }
  return lines;
}

}  // namespace adb::io::detail

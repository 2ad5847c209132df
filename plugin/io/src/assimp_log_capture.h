// AssimpLogCapture: collects assimp's warnings and errors for the duration of one load.
//
// assimp reports what it skips or cannot find (a missing .mtl file, say) only through its
// logger, and it has exactly one: Assimp::DefaultLogger, a process-wide singleton with no
// per-Importer alternative. That logger is not thread-safe (a plain vector of streams, and a
// "last message" buffer it uses to drop repeats), and creating or killing it while another
// thread logs is a use-after-free. So a capture holds one process-wide mutex for its whole
// lifetime: loads through adb::io run one at a time (reading files is I/O-bound anyway, and
// the mesh building after the read runs outside the lock).
//
// When the application has no assimp logger, the capture creates one (no default streams, so
// nothing is printed) and kills it afterwards. When it has one, the capture attaches a stream
// to it and detaches it afterwards, leaving the application's logger and streams in place; the
// application must then not use assimp from other threads during a load (nothing in adb can
// lock out code that does not take our mutex).
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace adb::io::detail {

class AssimpLogCapture {
 public:
  AssimpLogCapture();
  ~AssimpLogCapture();
  AssimpLogCapture(const AssimpLogCapture&) = delete;
  AssimpLogCapture& operator=(const AssimpLogCapture&) = delete;

  /// The warnings and errors logged so far, as "assimp error: <message>" / "assimp warning:
  /// <message>", in order; the capture starts empty again. At most 100 lines are kept (then
  /// one saying how many more came), each cut to an excerpt (message_text.h).
  std::vector<std::string> take();

 private:
  class Stream;
  std::unique_lock<std::mutex> m_lock;
  std::unique_ptr<Stream> m_stream;
  bool m_ownsLogger = false;
};

}  // namespace adb::io::detail

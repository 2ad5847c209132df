#include "isolated_read.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <new>
#include <vector>

namespace adb::io::detail {
namespace {

// Sanitizers reserve terabytes of address space: an address-space limit would stop them.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

// The child's message: a byte (1: a mesh, 0: an error), then the mesh and its report, or the
// error's text.
class Writer {
 public:
  template <class T>
  void put(const T& value) {
    const char* p = reinterpret_cast<const char*>(&value);
    m_bytes.insert(m_bytes.end(), p, p + sizeof(T));
  }
  void put(const std::string& s) {
    put<std::uint64_t>(s.size());
    m_bytes.insert(m_bytes.end(), s.begin(), s.end());
  }
  void send(int fd) const {
    std::size_t at = 0;
    while (at < m_bytes.size()) {
      const ssize_t n = ::write(fd, m_bytes.data() + at, m_bytes.size() - at);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return;
      at += static_cast<std::size_t>(n);
    }
  }

 private:
  std::vector<char> m_bytes;
};

class Reader {
 public:
  explicit Reader(const std::vector<char>& bytes) : m_bytes(bytes) {}
  template <class T>
  T get() {
    T value{};
    if (m_bytes.size() - m_at < sizeof(T)) throw std::runtime_error("short message");
    std::memcpy(&value, m_bytes.data() + m_at, sizeof(T));
    m_at += sizeof(T);
    return value;
  }
  std::string text() {
    const auto n = get<std::uint64_t>();
    if (m_bytes.size() - m_at < n) throw std::runtime_error("short message");
    std::string s(m_bytes.data() + m_at, static_cast<std::size_t>(n));
    m_at += static_cast<std::size_t>(n);
    return s;
  }
  std::size_t left() const { return m_bytes.size() - m_at; }

 private:
  const std::vector<char>& m_bytes;
  std::size_t m_at = 0;
};

[[noreturn]] void runChild(int fd, const std::function<std::pair<adb::TriangleMesh, LoadReport>()>& read,
                           const LoadLimits& limits) {
  // assimp prints its failed assertions before it aborts: the error the parent gives says it
  // all, and a sanitizer build keeps the child's reports (they are what a finding is).
  if (!kSanitized) {
    const int null = ::open("/dev/null", O_WRONLY);
    if (null >= 0) {
      ::dup2(null, STDOUT_FILENO);
      ::dup2(null, STDERR_FILENO);
      ::close(null);
    }
  }
  // The child is disposable: its crash is the parent's answer, not the application's, so the
  // application's crash handlers (a crash reporter, a fuzzer's) must not run for it.
  for (const int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGTRAP, SIGSYS}) {
    ::signal(sig, SIG_DFL);
  }
  if (!kSanitized && limits.maxReadBytes > 0) {
    const rlimit memory{static_cast<rlim_t>(limits.maxReadBytes), static_cast<rlim_t>(limits.maxReadBytes)};
    setrlimit(RLIMIT_AS, &memory);
  }
  Writer out;
  try {
    const auto [mesh, report] = read();
    out.put<std::uint8_t>(1);
    out.put<std::uint64_t>(mesh.vertices().size());
    for (const Vec3& v : mesh.vertices()) {
      for (int k = 0; k < 3; ++k) out.put(v[k]);
    }
    out.put<std::uint64_t>(mesh.triangles().size());
    for (const Triangle& t : mesh.triangles()) out.put(t);
    out.put<std::uint64_t>(report.warnings.size());
    for (const std::string& w : report.warnings) out.put(w);
    out.put<std::uint64_t>(report.sourceMeshes);
  } catch (const std::bad_alloc&) {
    out = Writer();
    out.put<std::uint8_t>(0);
    out.put(std::string("reading it needs more memory than the limit of ") +
            std::to_string(limits.maxReadBytes) + " bytes (LoadLimits::maxReadBytes)");
  } catch (const std::exception& e) {
    out = Writer();
    out.put<std::uint8_t>(0);
    out.put(std::string(e.what()));
  }
  out.send(fd);
  ::close(fd);
  _exit(0);  // no atexit handlers, no flushing of the parent's buffers
}

// Everything the child writes, until it closes the pipe or the deadline passes (false).
bool receive(int fd, double seconds, std::vector<char>& bytes) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  char buffer[1 << 16];
  for (;;) {
    const double left = std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
    if (left <= 0) return false;
    pollfd p{fd, POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::ceil(std::min(left, 3600.0) * 1000)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) return false;
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return true;
    bytes.insert(bytes.end(), buffer, buffer + n);
  }
}

std::string describeStatus(int status) {
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    const char* text = ::strsignal(sig);
    return "the reader crashed on it (signal " + std::to_string(sig) + ", " +
           (text ? text : "?") + "): assimp cannot read this file";
  }
  return "the reader stopped with status " + std::to_string(WEXITSTATUS(status)) +
         " before it answered";
}

}  // namespace

adb::TriangleMesh readIsolated(const std::function<std::pair<adb::TriangleMesh, LoadReport>()>& read,
                               const std::string& name, LoadReport* report,
                               const LoadLimits& limits) {
  int fds[2];
  if (::pipe(fds) != 0) throw MeshFileError(name + ": cannot start a reader (pipe: " + std::strerror(errno) + ")");
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw MeshFileError(name + ": cannot start a reader (fork: " + std::strerror(errno) + ")");
  }
  if (pid == 0) {
    ::close(fds[0]);
    runChild(fds[1], read, limits);
  }
  ::close(fds[1]);
  std::vector<char> bytes;
  const bool answered = receive(fds[0], limits.maxReadSeconds, bytes);
  ::close(fds[0]);
  if (!answered) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!answered) {
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%g", limits.maxReadSeconds);
    throw MeshFileError(name + ": reading it took longer than " + seconds +
                        " s (LoadLimits::maxReadSeconds)");
  }
  if (bytes.empty() || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw MeshFileError(name + ": " + describeStatus(status));
  }
  Reader in(bytes);
  try {
    if (in.get<std::uint8_t>() == 0) throw MeshFileError(in.text());
    // Counts are bounded by the message's own size.
    const auto vertices = std::min<std::uint64_t>(in.get<std::uint64_t>(), in.left() / (3 * sizeof(double)));
    std::vector<Vec3> v(static_cast<std::size_t>(vertices));
    for (Vec3& x : v) {
      const double a = in.get<double>(), b = in.get<double>(), c = in.get<double>();
      x = Vec3(a, b, c);
    }
    const auto triangles = std::min<std::uint64_t>(in.get<std::uint64_t>(), in.left() / sizeof(Triangle));
    std::vector<Triangle> t(static_cast<std::size_t>(triangles));
    for (Triangle& x : t) x = in.get<Triangle>();
    LoadReport r;
    const auto warnings = std::min<std::uint64_t>(in.get<std::uint64_t>(), in.left());
    for (std::uint64_t i = 0; i < warnings; ++i) r.warnings.push_back(in.text());
    r.sourceMeshes = static_cast<std::size_t>(in.get<std::uint64_t>());
    adb::TriangleMesh mesh(std::move(v), std::move(t), name);
    r.triangles = mesh.triangleCount();
    r.vertices = mesh.vertices().size();
    if (report) *report = std::move(r);
    return mesh;
  } catch (const MeshFileError&) {
    throw;
  } catch (const std::exception& e) {
    throw MeshFileError(name + ": the reader's answer is damaged (" + e.what() + ")");
  }
}

}  // namespace adb::io::detail

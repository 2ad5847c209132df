// Internal: WorkerPool, the scheduler's threads (oneTBB) for work that touches no Bullet state.
//
// Debian's Bullet is built without BT_THREADSAFE, so nothing of Bullet's may run off the
// thread that called stepSimulation. What may: a mesh-mesh pair's query, which reads the
// pair's two immutable trees and writes only its own traversal. The pool runs such jobs on a
// oneTBB task arena of the configured size, measures each thread's busy time, and hands any
// exception a job threw back to the caller, first in job order, once all jobs ended: nothing
// leaves a worker, and what leaves run() does not depend on which thread was faster.
#pragma once

#include <array>
#include <cstddef>
#include <exception>
#include <memory>
#include <vector>

namespace adb::detail {

class WorkerPool {
 public:
  static constexpr int kMaxTracked = 64;

  WorkerPool();
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  /// 0: all hardware threads; 1: none (jobs run on the calling thread); N: at most N.
  void configure(int threads);
  int threads() const { return m_threads; }

  /// job(i) for i in [0, n), on the pool's threads. Returns when all have ended; rethrows the
  /// exception of the lowest i that threw, if any.
  template <class Job>
  void run(std::size_t n, Job& job) {
    runErased(n, &job, [](void* context, std::size_t i) { (*static_cast<Job*>(context))(i); });
  }

  /// Wall clock of the last run(), and each thread's time in its jobs (thread k of the
  /// arena; threads beyond kMaxTracked add to the last slot).
  double lastWallMicros() const { return m_wallMicros; }
  const std::array<double, kMaxTracked>& lastBusyMicros() const { return m_busyMicros; }

 private:
  using Erased = void (*)(void*, std::size_t);
  void runErased(std::size_t n, void* context, Erased job);

  struct Arena;
  std::unique_ptr<Arena> m_arena;
  int m_threads = 1;
  std::vector<std::exception_ptr> m_errors;  // per job of the current run (reused)
  double m_wallMicros = 0.0;
  std::array<double, kMaxTracked> m_busyMicros{};
};

}  // namespace adb::detail

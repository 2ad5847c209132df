#include "worker_pool.h"

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/info.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>

namespace adb::detail {

struct WorkerPool::Arena {
  oneapi::tbb::task_arena arena;
  explicit Arena(int threads) : arena(threads) {}
};

WorkerPool::WorkerPool() = default;
WorkerPool::~WorkerPool() = default;

void WorkerPool::configure(int threads) {
  const int resolved = threads == 0 ? oneapi::tbb::info::default_concurrency() : threads;
  if (resolved == m_threads && (m_arena || resolved == 1)) return;
  m_threads = std::max(1, resolved);
  m_arena.reset();
  if (m_threads > 1) m_arena = std::make_unique<Arena>(m_threads);
}

void WorkerPool::runErased(std::size_t n, void* context, Erased job) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  m_busyMicros.fill(0.0);
  m_errors.assign(n, nullptr);
  // Per-slot busy time, each slot written by one thread at a time (a slot is a thread of
  // the arena), summed with relaxed atomics only where the arena has more threads than slots.
  std::array<std::atomic<double>, kMaxTracked> busy{};
  const auto body = [&](std::size_t i) {
    const Clock::time_point t0 = Clock::now();
    try {
      job(context, i);
    } catch (...) {
      m_errors[i] = std::current_exception();
    }
    const double us = std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
    int slot = m_arena ? oneapi::tbb::this_task_arena::current_thread_index() : 0;
    slot = std::clamp(slot, 0, kMaxTracked - 1);
    double seen = busy[static_cast<std::size_t>(slot)].load(std::memory_order_relaxed);
    while (!busy[static_cast<std::size_t>(slot)].compare_exchange_weak(
        seen, seen + us, std::memory_order_relaxed)) {
    }
  };
  if (!m_arena || n <= 1) {
    for (std::size_t i = 0; i < n; ++i) body(i);
  } else {
    // One job per task: a pair's query costs from a microsecond to milliseconds, so the
    // grain is the job, and oneTBB's stealing balances the long ones.
    m_arena->arena.execute([&] {
      oneapi::tbb::parallel_for(oneapi::tbb::blocked_range<std::size_t>(0, n, 1),
                                [&](const oneapi::tbb::blocked_range<std::size_t>& r) {
                                  for (std::size_t i = r.begin(); i != r.end(); ++i) body(i);
                                });
    });
  }
  for (int k = 0; k < kMaxTracked; ++k) {
    m_busyMicros[static_cast<std::size_t>(k)] = busy[static_cast<std::size_t>(k)].load();
  }
  m_wallMicros = std::chrono::duration<double, std::micro>(Clock::now() - start).count();
  for (const std::exception_ptr& e : m_errors) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace adb::detail

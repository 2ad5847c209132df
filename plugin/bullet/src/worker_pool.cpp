#include "worker_pool.h"

#include <algorithm>
#include <atomic>
#include <chrono>

#if ADB_WORKERS_STD_THREAD
#include <thread>
#else
#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/info.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>
#endif

namespace adb::detail {

#if ADB_WORKERS_STD_THREAD
// The ThreadSanitizer build's pool (CMakeLists.txt, ADB_TSAN): threads started for each run
// and joined at its end, taking jobs from one counter. Slower to start than oneTBB's arena,
// and visible to the sanitizer.
struct WorkerPool::Arena {
  int threads;
  explicit Arena(int n) : threads(n) {}
  template <class Body>
  void forEach(std::size_t n, Body& body) {
    std::atomic<std::size_t> next{0};
    const auto work = [&](int slot) {
      for (std::size_t i = next++; i < n; i = next++) body(i, slot);
    };
    std::vector<std::thread> helpers;
    for (int t = 1; t < threads; ++t) helpers.emplace_back(work, t);
    work(0);
    for (std::thread& h : helpers) h.join();
  }
};

namespace {
int hardwareThreads() {
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}
}  // namespace
#else
struct WorkerPool::Arena {
  oneapi::tbb::task_arena arena;
  explicit Arena(int threads) : arena(threads) {}
  // One job per task: a pair's query costs from a microsecond to milliseconds, so the grain
  // is the job, and oneTBB's stealing balances the long ones.
  template <class Body>
  void forEach(std::size_t n, Body& body) {
    arena.execute([&] {
      oneapi::tbb::parallel_for(oneapi::tbb::blocked_range<std::size_t>(0, n, 1),
                                [&](const oneapi::tbb::blocked_range<std::size_t>& r) {
                                  const int slot =
                                      oneapi::tbb::this_task_arena::current_thread_index();
                                  for (std::size_t i = r.begin(); i != r.end(); ++i) {
                                    body(i, slot);
                                  }
                                });
    });
  }
};

namespace {
int hardwareThreads() { return oneapi::tbb::info::default_concurrency(); }
}  // namespace
#endif

WorkerPool::WorkerPool() = default;
WorkerPool::~WorkerPool() = default;

void WorkerPool::configure(int threads) {
  const int resolved = threads == 0 ? hardwareThreads() : threads;
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
  const auto body = [&](std::size_t i, int slot) {
    const Clock::time_point t0 = Clock::now();
    try {
      job(context, i);
    } catch (...) {
      m_errors[i] = std::current_exception();
    }
    const double us = std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
    const int tracked = std::clamp(slot, 0, kMaxTracked - 1);
    std::atomic<double>& mine = busy[static_cast<std::size_t>(tracked)];
    double seen = mine.load(std::memory_order_relaxed);
    while (!mine.compare_exchange_weak(seen, seen + us, std::memory_order_relaxed)) {
    }
  };
  if (!m_arena || n <= 1) {
    for (std::size_t i = 0; i < n; ++i) body(i, 0);
  } else {
    m_arena->forEach(n, body);
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

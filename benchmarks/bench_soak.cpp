// adb-bench-soak: does a long-running world leak or slow down? A pile in a bin under
// adb::Dispatcher where every step some bodies are added and as many removed at random: mesh
// bodies sharing MeshData, mesh bodies with their own MeshData (built when they are added,
// freed with them), shapes with their own scaled tree (setLocalScaling) and Bullet's spheres
// and boxes. Every interval it prints the resident set size and the time per step; at the
// end a verdict: RSS growth from the end of the first interval to the end, and the time per
// step of the last interval against the second (the first includes the pile forming).
//
//   build/bin/adb-bench-soak [--steps 10000] [--interval 1000] [--bodies 50] [--churn 2]
//                            [--seed 1] [--budget-pairs N | --budget-us US]
#include <CLI/CLI.hpp>

#include <btBulletDynamicsCommon.h>
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "adb/bullet/dispatcher.h"
#include "adb/bullet/mesh_shape.h"
#include "adb/support/mesh_generators.h"
#include "shared/command_line.h"
#include "shared/progress.h"

namespace {

using Clock = std::chrono::steady_clock;

struct Options {
  int steps = 10000;
  int interval = 1000;
  int bodies = 50;
  int churn = 2;
  std::uint64_t seed = 1;
  std::uint64_t budgetPairs = 0;
  double budgetMicros = 0;
};

void addOptions(CLI::App& app, Options& o) {
  app.description(
      "adb-bench-soak: a pile whose bodies come and go (shared and own MeshData, scaled\n"
      "shapes, Bullet primitives); RSS and time per step every interval, and a verdict.");
  constexpr long long kNoLimit = std::numeric_limits<long long>::max();
  constexpr long long kMaxInt = std::numeric_limits<int>::max();
  adb::tools::addIntegerOption(app, "--steps", o.steps, 1, kMaxInt, "steps to run");
  adb::tools::addIntegerOption(app, "--interval", o.interval, 1, kMaxInt,
                              "steps per row of the table");
  adb::tools::addIntegerOption(app, "--bodies", o.bodies, 1, 100000,
                              "dynamic bodies alive at any time");
  adb::tools::addIntegerOption(app, "--churn", o.churn, 0, 100000,
                              "bodies added and as many removed every step (at most --bodies)");
  adb::tools::addIntegerOption(app, "--seed", o.seed, 0, kNoLimit,
                              "random seed (bodies, poses, removals)");
  adb::tools::addIntegerOption(app, "--budget-pairs", o.budgetPairs, 0, kNoLimit,
                              "node-pair budget per step (0: none)");
  adb::tools::addValueOption(
      app, "--budget-us", "US", "time budget per step in microseconds (0: none)",
      [&o](const std::string& text) {
        const double micros = adb::tools::parseNumber("--budget-us", text);
        if (micros < 0) adb::tools::failValue("--budget-us", text, "must be >= 0");
        o.budgetMicros = micros;
      },
      "0");
}

// Resident set size now, in MB (/proc/self/statm: pages).
double residentMB() {
  std::ifstream statm("/proc/self/statm");
  long long size = 0, resident = 0;
  statm >> size >> resident;
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / 1048576.0;
}

// The largest RSS so far, in MB (getrusage reports kilobytes on Linux).
double peakMB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

double uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

class SoakWorld {
 public:
  explicit SoakWorld(const Options& o)
      : m_rng(o.seed),
        m_configuration(adb::collisionConstructionInfo()),
        m_dispatcher(&m_configuration),
        m_world(&m_dispatcher, &m_broadphase, &m_solver, &m_configuration) {
    adb::FrameSettings settings;
    if (o.budgetPairs > 0) settings.budgetNodePairs = o.budgetPairs;
    if (o.budgetMicros > 0) settings.budgetMicros = o.budgetMicros;
    m_dispatcher.setFrameSettings(settings);
    m_world.setGravity(btVector3(0, -10, 0));
    // The shared meshes, in their principal frames (dynamic bodies).
    const auto principal = [](adb::TriangleMesh m) {
      return adb::MeshData::build(std::move(m), {}, adb::ShapeFrame::Principal);
    };
    m_shared = {principal(adb::gen::makeTorus(0.3, 0.1, 24, 12)),
                principal(adb::gen::makeGear(10, 0.3, 0.22, 0.08, 0.12, 4)),
                principal(adb::gen::makeTorusKnot(2, 3, 0.35, 0.05, 96, 8))};
    // A mesh floor (a closed cube scaled to a 6 x 1 x 6 m slab, its top at 0) and a bin of
    // Bullet boxes, 4 x 4 m inside, that keeps the pile together (one or two layers deep).
    auto floor = std::make_unique<adb::MeshShape>(
        adb::MeshData::build(adb::gen::makeBox(adb::Vec3(0.5, 0.5, 0.5), 4)));
    floor->setLocalScaling(btVector3(6, 1, 6));
    addStatic(std::move(floor), btVector3(0, -0.5f, 0));
    for (int side = 0; side < 4; ++side) {
      const btScalar sign = side % 2 ? btScalar(1) : btScalar(-1);
      const bool alongX = side < 2;
      addStatic(std::make_unique<btBoxShape>(alongX ? btVector3(2.5f, 1.5f, 0.25f)
                                                    : btVector3(0.25f, 1.5f, 2.5f)),
                alongX ? btVector3(0, 1.5f, sign * 2.25f) : btVector3(sign * 2.25f, 1.5f, 0));
    }
    for (int i = 0; i < o.bodies; ++i) addBody();
  }

  ~SoakWorld() {
    while (!m_bodies.empty()) removeBody(0);
    for (Body& s : m_statics) m_world.removeRigidBody(s.body.get());
  }

  void step() { m_world.stepSimulation(btScalar(1.0 / 60), 1, btScalar(1.0 / 60)); }

  /// Adds `n` bodies and removes `n` others, chosen at random among those alive.
  void churn(int n) {
    for (int i = 0; i < n; ++i) addBody();
    for (int i = 0; i < n; ++i) {
      removeBody(std::uniform_int_distribution<std::size_t>(0, m_bodies.size() - 1)(m_rng));
    }
  }

  std::size_t alive() const { return m_bodies.size(); }
  std::uint64_t added() const { return m_added; }
  std::uint64_t ownMeshes() const { return m_ownMeshes; }
  const adb::FrameStats& stats() const { return m_dispatcher.lastFrameStats(); }

 private:
  struct Body {
    std::unique_ptr<btCollisionShape> shape;
    std::unique_ptr<btRigidBody> body;
  };

  void addStatic(std::unique_ptr<btCollisionShape> shape, const btVector3& at) {
    btRigidBody::btRigidBodyConstructionInfo ci(0, nullptr, shape.get());
    ci.m_startWorldTransform.setOrigin(at);
    auto body = std::make_unique<btRigidBody>(ci);
    m_world.addRigidBody(body.get());
    m_statics.push_back({std::move(shape), std::move(body)});
  }

  // One new body above the pile: half share a MeshData, a quarter build their own (freed
  // when the body goes), one in twelve scales a shared one (its own scaled tree), the rest
  // are Bullet's spheres and boxes.
  void addBody() {
    const int kind = std::uniform_int_distribution<int>(0, 11)(m_rng);
    std::unique_ptr<btCollisionShape> shape;
    if (kind < 6) {
      shape = std::make_unique<adb::MeshShape>(m_shared[static_cast<std::size_t>(kind % 3)]);
    } else if (kind < 9) {
      shape = std::make_unique<adb::MeshShape>(adb::MeshData::build(
          kind == 6 ? adb::gen::makeTorus(uniform(m_rng, 0.2, 0.35), uniform(m_rng, 0.06, 0.1),
                                          16, 8)
                    : adb::gen::makeGear(8 + kind, uniform(m_rng, 0.25, 0.35), 0.2, 0.06,
                                         uniform(m_rng, 0.08, 0.15), 4),
          {}, adb::ShapeFrame::Principal));
      ++m_ownMeshes;
    } else if (kind == 9) {
      auto mesh = std::make_unique<adb::MeshShape>(m_shared[m_added % 3]);
      const btScalar s = btScalar(uniform(m_rng, 0.7, 1.3));
      mesh->setLocalScaling(btVector3(s, s, s));
      shape = std::move(mesh);
    } else if (kind == 10) {
      shape = std::make_unique<btSphereShape>(btScalar(uniform(m_rng, 0.1, 0.2)));
    } else {
      shape = std::make_unique<btBoxShape>(btVector3(btScalar(uniform(m_rng, 0.08, 0.2)),
                                                     btScalar(uniform(m_rng, 0.08, 0.2)),
                                                     btScalar(uniform(m_rng, 0.08, 0.2))));
    }
    btVector3 inertia(0, 0, 0);
    shape->calculateLocalInertia(1, inertia);
    btRigidBody::btRigidBodyConstructionInfo ci(1, nullptr, shape.get(), inertia);
    std::normal_distribution<double> n;
    const btQuaternion rotation(btScalar(n(m_rng)), btScalar(n(m_rng)), btScalar(n(m_rng)),
                                btScalar(n(m_rng)));
    ci.m_startWorldTransform = btTransform(
        rotation.normalized(), btVector3(btScalar(uniform(m_rng, -1.6, 1.6)),
                                         btScalar(uniform(m_rng, 1.5, 2.5)),
                                         btScalar(uniform(m_rng, -1.6, 1.6))));
    auto body = std::make_unique<btRigidBody>(ci);
    m_world.addRigidBody(body.get());
    m_bodies.push_back({std::move(shape), std::move(body)});
    ++m_added;
  }

  void removeBody(std::size_t i) {
    m_world.removeRigidBody(m_bodies[i].body.get());
    // Swap with the last: order does not matter, and removal stays O(1).
    std::swap(m_bodies[i], m_bodies.back());
    m_bodies.pop_back();
  }

  std::mt19937_64 m_rng;
  btDefaultCollisionConfiguration m_configuration;
  adb::Dispatcher m_dispatcher;
  btDbvtBroadphase m_broadphase;
  btSequentialImpulseConstraintSolver m_solver;
  btDiscreteDynamicsWorld m_world;
  std::vector<std::shared_ptr<const adb::MeshData>> m_shared;
  std::vector<Body> m_statics;
  std::vector<Body> m_bodies;
  std::uint64_t m_added = 0;
  std::uint64_t m_ownMeshes = 0;
};

struct Row {
  int step;
  double rss, peak;
  double stepMs, churnMs;  // per step, over the interval
  double pairs, otherPairs;  // adb pairs per step, over the interval
  // The step's time per adb pair: the pile's pair count wanders with the bodies that come
  // and go, and the time per step with it; a slowdown shows here.
  double microsPerPair() const { return 1e3 * stepMs / (pairs + otherPairs); }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"", "adb-bench-soak"};
  Options o;
  addOptions(app, o);
  if (const std::optional<int> exitCode =
          adb::tools::parseCommandLine(app, "adb-bench-soak", argc, argv)) {
    return *exitCode;
  }
  if (o.churn > o.bodies) {
    std::fprintf(stderr, "adb-bench-soak: error: --churn '%d': must be at most --bodies (%d)\n",
                 o.churn, o.bodies);
    return 2;
  }

  SoakWorld world(o);
  std::printf("adb-bench-soak: %d steps, %d bodies, %d added and %d removed per step, seed %llu,"
              " budget %s\n\n",
              o.steps, o.bodies, o.churn, o.churn, static_cast<unsigned long long>(o.seed),
              o.budgetPairs   ? (std::to_string(o.budgetPairs) + " node pairs").c_str()
              : o.budgetMicros ? (std::to_string(o.budgetMicros) + " us").c_str()
                               : "none");
  std::printf("%8s %8s %10s %10s %9s %9s %9s %9s %11s %9s\n", "step", "alive", "added",
              "own mesh", "RSS MB", "peak MB", "ms/step", "churn ms", "adb pairs", "us/pair");
  std::fflush(stdout);

  adb::tools::Progress progress(static_cast<std::uint64_t>(o.steps), "steps");
  std::vector<Row> rows;
  double stepSeconds = 0, churnSeconds = 0, pairs = 0, otherPairs = 0;
  int inInterval = 0;
  for (int step = 1; step <= o.steps; ++step) {
    const Clock::time_point t0 = Clock::now();
    world.churn(o.churn);
    const Clock::time_point t1 = Clock::now();
    world.step();
    const Clock::time_point t2 = Clock::now();
    churnSeconds += std::chrono::duration<double>(t1 - t0).count();
    stepSeconds += std::chrono::duration<double>(t2 - t1).count();
    pairs += world.stats().pairs;
    otherPairs += world.stats().otherPairs;
    ++inInterval;
    progress.advance();
    if (step % o.interval == 0 || step == o.steps) {
      const double n = inInterval;
      rows.push_back({step, residentMB(), peakMB(), 1e3 * stepSeconds / n, 1e3 * churnSeconds / n,
                      pairs / n, otherPairs / n});
      const Row& r = rows.back();
      progress.hide();
      std::printf("%8d %8zu %10llu %10llu %9.1f %9.1f %9.3f %9.3f %5.0f+%-5.0f %9.2f\n",
                  r.step, world.alive(), static_cast<unsigned long long>(world.added()),
                  static_cast<unsigned long long>(world.ownMeshes()), r.rss, r.peak, r.stepMs,
                  r.churnMs, r.pairs, r.otherPairs, r.microsPerPair());
      std::fflush(stdout);
      stepSeconds = churnSeconds = pairs = otherPairs = 0;
      inInterval = 0;
    }
  }
  progress.finish();

  // RSS from the end of the first interval (the pile formed, pools and caches warm) to the
  // end; time per step of the last interval against the second (the first has the pile
  // forming, fewer contacts).
  std::printf("\n(RSS: /proc/self/statm; peak: getrusage's ru_maxrss, counted a little "
              "differently; ms/step: stepSimulation alone; churn ms: adding and removing "
              "bodies, own meshes' trees built; adb pairs: mesh-mesh + other, per step; us/pair: "
              "ms/step over them)\n");
  if (rows.size() < 3) {
    std::printf("verdict: too few intervals for a verdict (%zu; need 3)\n", rows.size());
    return 0;
  }
  const Row& first = rows.front();
  const Row& second = rows[1];
  const Row& last = rows.back();
  const double growth = last.rss - first.rss;
  std::printf("verdict: RSS %+.1f MB (%+.1f %%) from step %d to %d; time per step %.3f ms in the "
              "last interval against %.3f ms in the second: ratio %.2f (per adb pair: %.2f)\n",
              growth, 100.0 * growth / first.rss, first.step, last.step, last.stepMs,
              second.stepMs, last.stepMs / second.stepMs,
              last.microsPerPair() / second.microsPerPair());
  return 0;
}

// ContactTrace: why a pile does not fall asleep. After each step of a dynamics scene it
// compares every pair's contact points (its manifolds together) with the step before and notes each body whose
// deactivation timer Bullet reset (the body moved faster than its sleeping thresholds):
//
// - contact churn, per step: points held, points that kept their identity (the same
//   features, m_index0/m_index1, as last step; points without features are matched as
//   Bullet matches them, the nearest within the breaking threshold), points new, moved over
//   `movedOver` (1 mm), whose normal turned over `turnedOver` (1 degree), and dropped;
// - timer resets, per body and step: its speed and spin, and the churn of that step on the
//   pairs it is part of.
//
// The same measure for every backend (adb, exact contacts, GImpact, convex hulls), read from
// Bullet's manifolds after the step. Untimed: it is not part of a step's cost.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <utility>
#include <vector>

#include "adb/scene/scene_world.h"

class btDiscreteDynamicsWorld;
class btDispatcher;

namespace adb::scene {

/// Contact events of one step, over some manifolds.
struct ContactChurn {
  std::uint32_t points = 0;     ///< points held after the step
  std::uint32_t keptId = 0;     ///< of those, with last step's features
  std::uint32_t matched = 0;    ///< of those, a point of last step's (by features or nearness)
  std::uint32_t fresh = 0;      ///< of those, new: no point of last step's
  std::uint32_t moved = 0;      ///< matched, and moved over the tolerance on either body
  std::uint32_t turned = 0;     ///< matched, and the normal turned over the tolerance
  std::uint32_t dropped = 0;    ///< last step's points no point of this step's matched
  void add(const ContactChurn& other);
};

class ContactTrace {
 public:
  /// Writes `folder`/contact_churn.csv and `folder`/sleep_resets.csv (created). Throws
  /// std::runtime_error naming a file it cannot write.
  ContactTrace(const std::filesystem::path& folder, double movedOver = 1e-3,
               double turnedOverDegrees = 1.0);
  /// After each step of `world` (a dynamics scene; others are ignored).
  void record(SceneWorld& world);
  /// The churn summed over every step so far.
  const ContactChurn& total() const { return m_total; }
  /// Timer resets so far.
  std::uint64_t resets() const { return m_resets; }

 private:
  struct Point {
    int index0, index1;
    double onA[3], onB[3], normal[3];
  };
  /// A body pair's points after a step, its manifolds together, and the largest breaking
  /// threshold among them (points without features are matched within it).
  struct PairPoints {
    double threshold = 0.0;
    std::vector<Point> points;
  };
  using PairKey = std::pair<const void*, const void*>;
  using Pairs = std::map<PairKey, PairPoints>;
  /// A body's churn over the pairs it is part of, and how many they are.
  struct BodyChurn {
    ContactChurn churn;
    int pairs = 0;
  };

  static Pairs pairsOf(btDispatcher& dispatcher);
  /// `now`'s points against `before`'s (null: the pair is new).
  ContactChurn compare(const PairPoints& now, const PairPoints* before) const;
  /// Writes a sleep_resets.csv row per body whose timer reset; returns how many did, and the
  /// bodies awake in `awake`.
  int writeResets(btDiscreteDynamicsWorld& dynamics, int step,
                  std::map<const void*, BodyChurn>& bodies, int& awake);

  std::ofstream m_churn, m_resetsFile;
  double m_moved, m_turnedCos;
  Pairs m_last;                            // every pair's points after last step
  std::map<const void*, double> m_timers;  // each body's deactivation time
  ContactChurn m_total;
  std::uint64_t m_resets = 0;
};

}  // namespace adb::scene

// The one interface every measured method sits behind (ADB modes, exact mode, GImpact, FCL,
// the box-only baselines): prepare its data structures for a pair of models once, then answer
// posed queries of the first against the second (a model against itself, in Zachmann's
// benchmark, when both are the same object).
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>

#include "adb/core/geometry.h"
#include "adb/core/mesh.h"

namespace adb::tradeoff {

/// A model under study: its label (model name or file stem), a key unique within the run
/// (2 x its case's position on the command line, + 1 for a case's second model; trees are
/// cached by it) and the mesh.
struct Model {
  std::string label;
  std::size_t index = 0;
  TriangleMesh mesh;
};

/// One method's answer to one query.
struct Answer {
  bool collides = false;
  double confidence = 1.0;       ///< the method's estimate that the answer is right
  std::int64_t nodePairs = -1;   ///< node pairs evaluated; -1 when the method cannot tell
};

/// The parameters of a method's setting, written to the p_min, k_min and budget_us columns.
struct MethodParams {
  bool hasQuality = false;  ///< ADB traversals: p_min and k_min apply
  double pMin = 0.0;
  int kMin = 0;
  double budgetUs = std::numeric_limits<double>::infinity();  ///< infinity: no time budget
  std::uint64_t budgetPairs = 0;  ///< a work budget in node pairs; 0: none (adb-work:N)
  /// The confidence is the method's own estimate (ADB, or a traversal a budget may cut), so
  /// its calibration is measured (reliability.csv, ece); exact methods report 1 and trivial
  /// ones a fixed 0.5, which have nothing to calibrate.
  bool estimates = false;
};

class Method {
 public:
  virtual ~Method() = default;
  /// "adb", "adb-work:N", "exact", "exact-cut", "box-first", "root-boxes", "gimpact" or
  /// "fcl".
  virtual const std::string& name() const = 0;
  virtual MethodParams params() const { return {}; }
  /// Builds what the method needs for model `a` and model `b` (untimed), called once per
  /// case. `b` is `a` itself (the same object) for two copies of one model: then the method
  /// builds one structure and queries it against itself.
  virtual void prepare(const Model& a, const Model& b) = 0;
  /// Tests the prepared model a at pose `a` against the prepared model b at pose `b`.
  virtual Answer query(const Pose& a, const Pose& b) = 0;
};

}  // namespace adb::tradeoff

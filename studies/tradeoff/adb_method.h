// The project's own ADB-tree as a measured method: the ADB traversal at one (p_min, k_min,
// time or work budget) setting, or the tree's exact mode (with or without a time budget).
// All of them share one tree per model (two for a pair of different models).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "adb/core/query.h"
#include "adb/core/tree.h"
#include "method.h"

namespace adb::tradeoff {

/// One ADB-tree per model, built once and shared by every ADB and exact method, with one
/// QueryScratch reused by all their queries (so queries do not allocate). It holds the trees
/// of one case: one model's, or a pair's two.
class SharedTree {
 public:
  /// Trees are built with `settings` (validated by the tree's constructor).
  explicit SharedTree(const BuildSettings& settings = {}) : m_settings(settings) {}

  /// Holds the trees of `a` and `b` (one tree when they are one model), building what it
  /// does not hold yet after freeing the trees of other models (1M-triangle models).
  void prepare(const Model& a, const Model& b);
  /// The tree of `model`: held since prepare(), else built as prepare(model, model) builds
  /// it.
  const AdbTree& treeFor(const Model& model);
  QueryScratch& scratch() { return m_scratch; }

 private:
  struct Held {
    std::size_t modelIndex;  ///< Model::index, not the model's address: a later model may be
                             ///< allocated where an earlier one was
    std::unique_ptr<AdbTree> tree;
  };
  const AdbTree* find(const Model& model) const;

  BuildSettings m_settings;
  std::vector<Held> m_trees;  ///< at most two
  QueryScratch m_scratch;
};

class AdbMethod : public Method {
 public:
  /// An ADB method (settings.mode == Adb: "adb", or "adb-work:N" under a work budget) or
  /// the exact mode ("exact", or "exact-cut" under a time budget). `name` is the method
  /// name written to the files.
  AdbMethod(std::shared_ptr<SharedTree> shared, const QuerySettings& settings,
            std::string name);

  const std::string& name() const override { return m_name; }
  MethodParams params() const override;
  void prepare(const Model& a, const Model& b) override;
  Answer query(const Pose& a, const Pose& b) override;

 private:
  std::shared_ptr<SharedTree> m_shared;
  QuerySettings m_settings;
  std::string m_name;
  const AdbTree* m_treeA = nullptr;
  const AdbTree* m_treeB = nullptr;
};

}  // namespace adb::tradeoff

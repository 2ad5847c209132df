// The project's own ADB-tree as a measured method: the ADB traversal at one (p_min, k_min,
// time or work budget) setting, or the tree's exact mode (with or without a time budget).
// All of them share one tree per model.
#pragma once

#include <memory>
#include <string>

#include "adb/core/query.h"
#include "adb/core/tree.h"
#include "method.h"

namespace adb::tradeoff {

/// One ADB-tree per model, built once and shared by every ADB and exact method, with one
/// QueryScratch reused by all their queries (so queries do not allocate).
class SharedTree {
 public:
  /// Trees are built with `settings` (validated by the tree's constructor).
  explicit SharedTree(const BuildSettings& settings = {}) : m_settings(settings) {}

  /// The tree of `model`, built when the model changes.
  const AdbTree& treeFor(const Model& model);
  QueryScratch& scratch() { return m_scratch; }

 private:
  BuildSettings m_settings;
  std::size_t m_modelIndex = static_cast<std::size_t>(-1);
  std::unique_ptr<AdbTree> m_tree;
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
  void prepare(const Model& model) override;
  Answer query(const Pose& a, const Pose& b) override;

 private:
  std::shared_ptr<SharedTree> m_shared;
  QuerySettings m_settings;
  std::string m_name;
  const AdbTree* m_tree = nullptr;
};

}  // namespace adb::tradeoff

// ADB and exact-mode queries on the shared per-model ADB-tree.
#include "adb_method.h"

#include <cmath>
#include <limits>

namespace adb::tradeoff {

const AdbTree& SharedTree::treeFor(const Model& model) {
  // Keyed by the model's command-line position, not its address: a later model may be
  // allocated where an earlier one was.
  if (!m_tree || m_modelIndex != model.index) {
    m_tree.reset();  // free the old tree before building the next (1M-triangle models)
    m_tree = std::make_unique<AdbTree>(model.mesh, m_settings);
    m_modelIndex = model.index;
  }
  return *m_tree;
}

AdbMethod::AdbMethod(std::shared_ptr<SharedTree> shared, const QuerySettings& settings,
                     std::string name)
    : m_shared(std::move(shared)), m_settings(settings), m_name(std::move(name)) {
  validate(m_settings);
}

MethodParams AdbMethod::params() const {
  MethodParams p;
  const bool adb = m_settings.mode == QueryMode::Adb;
  const bool workBudget =
      m_settings.budgetNodePairs != std::numeric_limits<std::uint64_t>::max();
  p.hasQuality = adb;
  p.pMin = adb ? m_settings.pMin : 0.0;
  p.kMin = adb ? m_settings.kMin : 0;
  p.budgetUs = m_settings.budgetMicros;
  p.budgetPairs = workBudget ? m_settings.budgetNodePairs : 0;
  // Exact mode's confidence is the model's estimate only where a budget may cut it; run to
  // the end it is always 1.
  p.estimates = adb || std::isfinite(p.budgetUs) || workBudget;
  return p;
}

void AdbMethod::prepare(const Model& model) { m_tree = &m_shared->treeFor(model); }

Answer AdbMethod::query(const Pose& a, const Pose& b) {
  const QueryResult r = collide(*m_tree, a, *m_tree, b, m_settings, m_shared->scratch());
  Answer answer;
  answer.collides = r.collides;
  answer.confidence = r.confidence;
  answer.nodePairs = static_cast<std::int64_t>(r.nodePairs);
  return answer;
}

}  // namespace adb::tradeoff

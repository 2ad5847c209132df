// ADB and exact-mode queries on the shared per-model ADB-trees.
#include "adb_method.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace adb::tradeoff {

const AdbTree* SharedTree::find(const Model& model) const {
  for (const Held& h : m_trees) {
    if (h.modelIndex == model.index) return h.tree.get();
  }
  return nullptr;
}

void SharedTree::prepare(const Model& a, const Model& b) {
  // Free the trees of other models before building (1M-triangle models).
  m_trees.erase(std::remove_if(m_trees.begin(), m_trees.end(),
                               [&](const Held& h) {
                                 return h.modelIndex != a.index && h.modelIndex != b.index;
                               }),
                m_trees.end());
  for (const Model* model : {&a, &b}) {
    if (!find(*model)) {
      m_trees.push_back(Held{model->index, std::make_unique<AdbTree>(model->mesh, m_settings)});
    }
  }
}

const AdbTree& SharedTree::treeFor(const Model& model) {
  if (const AdbTree* held = find(model)) return *held;
  prepare(model, model);
  return *find(model);
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

void AdbMethod::prepare(const Model& a, const Model& b) {
  m_shared->prepare(a, b);
  m_treeA = &m_shared->treeFor(a);
  m_treeB = &m_shared->treeFor(b);
}

Answer AdbMethod::query(const Pose& a, const Pose& b) {
  const QueryResult r = collide(*m_treeA, a, *m_treeB, b, m_settings, m_shared->scratch());
  Answer answer;
  answer.collides = r.collides;
  answer.confidence = r.confidence;
  answer.nodePairs = static_cast<std::int64_t>(r.nodePairs);
  return answer;
}

}  // namespace adb::tradeoff

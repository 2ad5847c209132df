// ContactAudit: a step's plausible contacts judged against the triangles (contact_audit.h).
#include "contact_audit.h"

#include "adb/core/node_triangles.h"

#include <algorithm>
#include <limits>

#include "adb/core/triangle_distance.h"
#include "adb/core/triangle_test.h"
#include "conversions.h"

namespace adb::detail {
namespace {

std::uint64_t key(std::uint32_t triangleA, std::uint32_t triangleB) {
  return (static_cast<std::uint64_t>(triangleA) << 32) | triangleB;
}

bool within(std::uint32_t t, std::uint32_t first, std::uint32_t end) {
  return first <= t && t < end;
}

// Whether boxes [loX, hiX] and [loY, hiY] come within `gap` of each other on every axis.
bool boxesNear(const Vec3& loX, const Vec3& hiX, const Vec3& loY, const Vec3& hiY, double gap) {
  return !((loX.array() > hiY.array() + gap).any() || (loY.array() > hiX.array() + gap).any());
}

}  // namespace

void ContactAudit::poseTriangles(const AdbTree& tree, const Pose& pose, std::uint32_t node,
                                 std::vector<WorldTriangle>& out, Vec3& lo, Vec3& hi) {
  const auto [first, end] = trianglesBelow(tree, node);
  out.clear();
  lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  hi = -lo;
  for (std::uint32_t t = first; t < end; ++t) {
    WorldTriangle w;
    worldTriangle(tree, pose, t, w.v);
    w.lo = w.v[0].cwiseMin(w.v[1]).cwiseMin(w.v[2]);
    w.hi = w.v[0].cwiseMax(w.v[1]).cwiseMax(w.v[2]);
    lo = lo.cwiseMin(w.lo);
    hi = hi.cwiseMax(w.hi);
    out.push_back(w);
  }
}

NodeProximity ContactAudit::proximity(const PosedPair& posed, std::uint32_t a, std::uint32_t b,
                                      double margin, double reach) {
  reach = std::max(reach, margin);
  Vec3 loA, hiA, loB, hiB;
  poseTriangles(*posed.a, posed.poseA, a, m_a, loA, hiA);
  poseTriangles(*posed.b, posed.poseB, b, m_b, loB, hiB);
  // Only triangles whose boxes come within reach of the other node's triangles can: the
  // boxes only skip pairs that are certainly farther apart, so the verdict is brute force's.
  const auto farFromB = [&](const WorldTriangle& t) {
    return !boxesNear(t.lo, t.hi, loB, hiB, reach);
  };
  const auto farFromA = [&](const WorldTriangle& t) {
    return !boxesNear(t.lo, t.hi, loA, hiA, reach);
  };
  m_a.erase(std::remove_if(m_a.begin(), m_a.end(), farFromB), m_a.end());
  m_b.erase(std::remove_if(m_b.begin(), m_b.end(), farFromA), m_b.end());
  NodeProximity p;
  for (const WorldTriangle& x : m_a) {
    for (const WorldTriangle& y : m_b) {
      if (!boxesNear(x.lo, x.hi, y.lo, y.hi, reach)) continue;
      if (trianglesIntersect(x.v[0], x.v[1], x.v[2], y.v[0], y.v[1], y.v[2])) {
        return {true, true};
      }
      // Within reach already, and without a margin only a crossing pair can tell more.
      if (p.withinReach && !(margin > 0.0)) continue;
      const double d = triangleDistance(x.v[0], x.v[1], x.v[2], y.v[0], y.v[1], y.v[2]).distance;
      if (d <= reach) p.withinReach = true;
      if (d <= margin) return {true, true};
    }
  }
  return p;
}

void ContactAudit::audit(const PairEvidence& pair, const FrameSettings& settings,
                         ContactAuditStats& stats, std::vector<AuditedContact>& contacts) {
  const PosedPair& posed = pair.posed;
  ++stats.pairs;
  // The accepted plausible contacts, chosen again as the pair's contacts were.
  PlausibleChoices chosen;
  const int count = selectPlausible(*posed.a, *posed.b, *pair.open, settings, chosen);
  std::array<std::array<std::uint32_t, 4>, kMaxPlausibleContacts> covered;
  for (int i = 0; i < count; ++i) {
    const NodeProximity near =
        proximity(posed, chosen[i].a, chosen[i].b, pair.margin, pair.threshold);
    ++stats.accepted;
    stats.ghosts += near.withinMargin ? 0 : 1;
    stats.farGhosts += near.withinReach ? 0 : 1;
    AuditedContact c;
    c.body0 = pair.body0;
    c.body1 = pair.body1;
    c.treeA = posed.a;
    c.treeB = posed.b;
    c.poseA = posed.poseA;
    c.poseB = posed.poseB;
    c.nodeA = chosen[i].a;
    c.nodeB = chosen[i].b;
    c.probability = chosen[i].probability;
    c.margin = pair.margin;
    c.threshold = std::max(pair.margin, pair.threshold);
    c.ghost = !near.withinMargin;
    c.farGhost = !near.withinReach;
    contacts.push_back(c);
    const auto ra = trianglesBelow(*posed.a, chosen[i].a);
    const auto rb = trianglesBelow(*posed.b, chosen[i].b);
    covered[i] = {ra.first, ra.second, rb.first, rb.second};
  }

  // What the cut query found: its exact witnesses.
  m_found.clear();
  for (const Witness& w : *pair.found) {
    if (w.isExact()) m_found.push_back(key(w.triangleA, w.triangleB));
  }
  std::sort(m_found.begin(), m_found.end());

  // The exact contacts at the same poses: every triangle pair within the same margin, in the
  // trees' order, no budget, no sampling.
  QuerySettings q;
  q.mode = QueryMode::Exact;
  q.stopAtFirstHit = false;
  q.maxWitnesses = ContactAuditStats::kMaxExactPairs;
  q.contactMargin = pair.margin;
  q.descent = ExactDescent::TreeOrder;
  m_exact.reset(*posed.a, posed.poseA, *posed.b, posed.poseB, q);
  if (m_exact.step().witnessesDropped > 0) ++stats.cappedPairs;

  bool openRanges = false;  // worked out on the first miss: most pairs miss nothing
  for (const Witness& w : m_exact.witnesses()) {
    if (!w.isExact()) continue;
    ++stats.exact;
    if (std::binary_search(m_found.begin(), m_found.end(), key(w.triangleA, w.triangleB))) {
      continue;
    }
    const auto below = [&w](const std::array<std::uint32_t, 4>& range) {
      return within(w.triangleA, range[0], range[1]) && within(w.triangleB, range[2], range[3]);
    };
    if (std::any_of(covered.begin(), covered.begin() + count, below)) continue;
    ++stats.missed;
    if (!openRanges) {
      m_openRanges.clear();
      for (const OpenPair& o : *pair.open) {
        const auto ra = trianglesBelow(*posed.a, o.a);
        const auto rb = trianglesBelow(*posed.b, o.b);
        m_openRanges.push_back({ra.first, ra.second, rb.first, rb.second});
      }
      openRanges = true;
    }
    if (std::any_of(m_openRanges.begin(), m_openRanges.end(), below)) ++stats.missedOpen;
  }
}

}  // namespace adb::detail

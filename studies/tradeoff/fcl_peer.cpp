// FCL peer: each model is built once per case (OBBRSS hierarchy in the mesh's coordinates; one
// for two copies of a model); each query passes the two poses as transforms, so nothing is
// refitted per query.
#include "fcl_peer.h"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>

#include <stdexcept>
#include <vector>

namespace adb::tradeoff {

namespace {

using Bvh = fcl::BVHModel<fcl::OBBRSSd>;

std::shared_ptr<Bvh> buildBvh(const Model& model) {
  std::vector<fcl::Vector3d> vertices(model.mesh.vertices().begin(), model.mesh.vertices().end());
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(model.mesh.triangleCount());
  for (const Triangle& t : model.mesh.triangles()) triangles.emplace_back(t[0], t[1], t[2]);
  auto bvh = std::make_shared<Bvh>();
  if (bvh->beginModel(static_cast<int>(triangles.size()), static_cast<int>(vertices.size())) !=
          fcl::BVH_OK ||
      bvh->addSubModel(vertices, triangles) != fcl::BVH_OK || bvh->endModel() != fcl::BVH_OK) {
    throw std::runtime_error("FCL could not build its BVH for " + model.label);
  }
  return bvh;
}

}  // namespace

struct FclPeer::Impl {
  std::shared_ptr<Bvh> modelA, modelB;  // one object for two copies of a model
  // num_max_contacts 1, no contact data: stop at the first intersecting triangle pair.
  fcl::CollisionRequestd request{1, false};
};

FclPeer::FclPeer() : m_impl(std::make_unique<Impl>()) {}
FclPeer::~FclPeer() = default;

void FclPeer::prepare(const Model& a, const Model& b) {
  m_impl->modelA.reset();  // free the last case's models first
  m_impl->modelB.reset();
  m_impl->modelA = buildBvh(a);
  m_impl->modelB = &a == &b ? m_impl->modelA : buildBvh(b);
}

Answer FclPeer::query(const Pose& a, const Pose& b) {
  fcl::Transform3d ta = fcl::Transform3d::Identity();
  ta.linear() = a.rotation;
  ta.translation() = a.translation;
  fcl::Transform3d tb = fcl::Transform3d::Identity();
  tb.linear() = b.rotation;
  tb.translation() = b.translation;
  fcl::CollisionResultd result;
  fcl::collide(m_impl->modelA.get(), ta, m_impl->modelB.get(), tb, m_impl->request, result);
  Answer answer;
  answer.collides = result.isCollision();
  answer.confidence = 1.0;
  return answer;  // nodePairs stays -1: FCL's BV-test count is not exposed by collide()
}

}  // namespace adb::tradeoff

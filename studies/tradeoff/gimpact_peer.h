// Bullet's GImpact as a measured peer: btGImpactMeshShape over each model's triangles and
// btGImpactCollisionAlgorithm, driven directly (findAlgorithm with
// BT_CONTACT_POINT_ALGORITHMS + processCollision: GImpact registers only contact-point
// algorithms, so contactPairTest would silently report nothing). "Collides" = the contact
// manifold has at least one point. GImpact always computes the full contact set, which is
// what Bullet's dynamics needs; its time is that of a contact query, not of a yes/no one.
#pragma once

#include <memory>
#include <string>

#include "method.h"

namespace adb::tradeoff {

class GimpactPeer : public Method {
 public:
  GimpactPeer();
  ~GimpactPeer() override;

  const std::string& name() const override { return m_name; }
  void prepare(const Model& a, const Model& b) override;
  Answer query(const Pose& a, const Pose& b) override;

 private:
  struct Impl;  // Bullet objects
  std::unique_ptr<Impl> m_impl;
  std::string m_name = "gimpact";
};

}  // namespace adb::tradeoff

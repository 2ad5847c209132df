// PileScene: builds the bin and the bodies for the chosen backend and measures each step.
#include "pile_scene.h"

#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>
#include <BulletCollision/Gimpact/btGImpactShape.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>

#include "adb/bullet/triangle_arrays.h"
#include "pile/convex_decomposition.h"
#include "adb/scene/penetration_probe.h"
#include "adb/bullet/dispatcher.h"
#include "adb/bullet/registration.h"
#include "adb/bullet/mesh_shape.h"
#include "adb/support/benchmark_poses.h"
#include "adb/support/mesh_generators.h"

namespace adb::demo {
namespace {

using scene::measurePenetration;
using scene::PenetrationReport;
using scene::ProbeBody;

constexpr double kGravity = 9.81;
constexpr double kFloorTop = 0.0;
// The walls' inner faces are 2.5 from the centre: a body centre beyond them has left the bin.
constexpr double kBinInside = 2.5;
// The convex backend's hull margin. Bullet grows a btConvexHullShape outwards by its margin
// (0.04 by default: 5 % of a 0.8 body, which would keep bodies apart by a visible gap and hide
// penetration from the probe); 0.01 is the margin GImpact's triangles get by default.
constexpr double kHullMargin = 0.01;

btVector3 toBt(const Vec3& v) {
  return btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()),
                   static_cast<btScalar>(v.z()));
}

// As adb::scene places bodies: the rotation as a matrix, entry by entry.
btTransform toBt(const Pose& p) {
  btMatrix3x3 basis;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) basis[r][c] = static_cast<btScalar>(p.rotation(r, c));
  }
  return btTransform(basis, toBt(p.translation));
}

// The three kinds of body, at about `triangles` triangles each, ~0.8 units across.
std::vector<TriangleMesh> bodyMeshes(std::size_t triangles) {
  const double t = static_cast<double>(triangles);
  const int ring = std::max(6, static_cast<int>(std::sqrt(t / 4.0)));
  const int tooth = std::max(4, static_cast<int>(t / 80.0));
  const int along = std::max(24, static_cast<int>(t / 16.0));
  return {gen::makeTorus(0.35, 0.12, 2 * ring, ring),
          gen::makeGear(10, 0.4, 0.32, 0.15, 0.15, tooth),
          gen::makeTorusKnot(2, 3, 0.3, 0.045, along, 8)};
}

// A mesh scaled about its bounds' centre so that its largest extent is `size` (the generated
// bodies are about 0.8 across): files come in any unit.
TriangleMesh scaledTo(const TriangleMesh& mesh, double size) {
  const Vec3 centre = mesh.bounds().center();
  const double extent = mesh.bounds().extent().maxCoeff();
  const double k = extent > 0 ? size / extent : 1.0;
  std::vector<Vec3> vertices;
  vertices.reserve(mesh.vertices().size());
  for (const Vec3& v : mesh.vertices()) vertices.push_back((v - centre) * k);
  return TriangleMesh(std::move(vertices), mesh.triangles(), mesh.name());
}

struct Box {
  Vec3 half, centre;
};

// The bin: a floor whose top is y = 0 and four walls (the floor first: Floor::Plane replaces it).
const Box kBin[] = {{Vec3(2.5, 0.25, 2.5), Vec3(0, -0.25, 0)},
                    {Vec3(0.25, 1.5, 2.5), Vec3(2.75, 1.25, 0)},
                    {Vec3(0.25, 1.5, 2.5), Vec3(-2.75, 1.25, 0)},
                    {Vec3(2.5, 1.5, 0.25), Vec3(0, 1.25, 2.75)},
                    {Vec3(2.5, 1.5, 0.25), Vec3(0, 1.25, -2.75)}};

}  // namespace

struct PileScene::Impl {
  std::unique_ptr<btDefaultCollisionConfiguration> configuration;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  Dispatcher* adbDispatcher = nullptr;  // the same object, under the adb backend
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  std::unique_ptr<btDiscreteDynamicsWorld> world;
  std::vector<std::unique_ptr<TriangleArrays>> indexed;  // what GImpact/BVH shapes read
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  std::vector<std::shared_ptr<const MeshData>> kinds;  // the bodies' meshes, by kind
  std::vector<std::vector<Vec3>> usedVertices;         // per kind of body
  std::vector<const std::vector<Vec3>*> bodyVertices;  // per dynamic body, its kind's used ones
  std::vector<double> bodySize;               // per dynamic body, its bounding-box diagonal
  std::vector<const AdbTree*> bodyTree;       // per dynamic body, its kind's tree (the probe)

  ~Impl() {
    for (auto& b : bodies) world->removeRigidBody(b.get());
  }

  btRigidBody* addBody(btCollisionShape* shape, double mass, const Vec3& inertia,
                       const btTransform& at) {
    btRigidBody::btRigidBodyConstructionInfo ci(static_cast<btScalar>(mass), nullptr, shape,
                                                toBt(inertia * mass));
    ci.m_startWorldTransform = at;
    ci.m_friction = btScalar(0.6);
    bodies.push_back(std::make_unique<btRigidBody>(ci));
    world->addRigidBody(bodies.back().get());
    return bodies.back().get();
  }

  // A shape of this scene's backend for `mesh`; `dynamic` picks GImpact over a static BVH.
  btCollisionShape* makeShape(const std::shared_ptr<const MeshData>& data, bool adb,
                              bool dynamic) {
    if (adb) {
      shapes.push_back(std::make_unique<MeshShape>(data));
      return shapes.back().get();
    }
    indexed.push_back(std::make_unique<TriangleArrays>(data->mesh));
    if (dynamic) {
      auto gimpact = std::make_unique<btGImpactMeshShape>(indexed.back()->array.get());
      gimpact->updateBound();
      shapes.push_back(std::move(gimpact));
    } else {
      shapes.push_back(std::make_unique<btBvhTriangleMeshShape>(indexed.back()->array.get(), true));
    }
    return shapes.back().get();
  }

  // The convex backend's body: the hulls as children of a compound, in the mesh's frame (the
  // principal frame, as for the other backends: no child offset, the same inertia).
  btCollisionShape* makeCompound(const ConvexDecomposition& parts) {
    auto compound = std::make_unique<btCompoundShape>(true, static_cast<int>(parts.hulls.size()));
    for (const std::vector<Vec3>& hull : parts.hulls) {
      auto child = std::make_unique<btConvexHullShape>();
      for (const Vec3& v : hull) child->addPoint(toBt(v), false);
      child->recalcLocalAabb();
      child->setMargin(static_cast<btScalar>(kHullMargin));
      compound->addChildShape(btTransform::getIdentity(), child.get());
      shapes.push_back(std::move(child));
    }
    shapes.push_back(std::move(compound));
    return shapes.back().get();
  }
};

PileScene::PileScene(const SceneSettings& settings) : m_impl(std::make_unique<Impl>()) {
  Impl& s = *m_impl;
  const bool adb = settings.backend == Backend::Adb;
  s.configuration = std::make_unique<btDefaultCollisionConfiguration>(collisionConstructionInfo());
  if (adb) {
    auto dispatcher = std::make_unique<Dispatcher>(s.configuration.get());
    dispatcher->setFrameSettings(settings.frame);
    s.adbDispatcher = dispatcher.get();
    s.dispatcher = std::move(dispatcher);
  } else {
    s.dispatcher = std::make_unique<btCollisionDispatcher>(s.configuration.get());
    btGImpactCollisionAlgorithm::registerAlgorithm(s.dispatcher.get());
  }
  s.world = std::make_unique<btDiscreteDynamicsWorld>(s.dispatcher.get(), &s.broadphase,
                                                      &s.solver, s.configuration.get());
  s.world->setGravity(btVector3(0, static_cast<btScalar>(-kGravity), 0));
  // No swept boxes: no body has CCD, and adb::scene builds worlds without it the same way.
  s.world->getDispatchInfo().m_useContinuous = false;

  bool first = true;
  for (const Box& b : kBin) {
    btTransform at = btTransform::getIdentity();
    at.setOrigin(toBt(b.centre));
    btCollisionShape* shape = nullptr;
    if (settings.floor == Floor::Plane && first) {
      // The floor's top, y = kFloorTop: the plane is y = 0 through the origin.
      s.shapes.push_back(std::make_unique<btStaticPlaneShape>(btVector3(0, 1, 0),
                                                              static_cast<btScalar>(kFloorTop)));
      shape = s.shapes.back().get();
      at.setOrigin(btVector3(0, 0, 0));
    } else if (settings.floor != Floor::Mesh) {
      s.shapes.push_back(std::make_unique<btBoxShape>(toBt(b.half)));
      shape = s.shapes.back().get();
    } else {
      shape = s.makeShape(MeshData::build(gen::makeBox(b.half, 4)), adb, false);
    }
    s.addBody(shape, 0.0, Vec3::Zero(), at);
    first = false;
  }

  std::vector<std::shared_ptr<const MeshData>>& kinds = s.kinds;
  if (settings.meshes.empty()) {
    for (TriangleMesh& mesh : bodyMeshes(settings.trianglesPerBody)) {
      kinds.push_back(MeshData::build(std::move(mesh), BuildSettings{}, ShapeFrame::Principal));
    }
  } else {
    for (const TriangleMesh& mesh : settings.meshes) {
      kinds.push_back(MeshData::build(scaledTo(mesh, 0.8), BuildSettings{}, ShapeFrame::Principal));
    }
  }
  const int kindCount = static_cast<int>(kinds.size());
  // The vertices the triangles use, per kind: a file may hold others, anywhere.
  s.usedVertices.resize(kinds.size());
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    const TriangleMesh& mesh = kinds[k]->mesh;
    std::vector<bool> used(mesh.vertices().size(), false);
    for (const Triangle& t : mesh.triangles()) {
      for (std::uint32_t v : t) used[v] = true;
    }
    for (std::size_t v = 0; v < used.size(); ++v) {
      if (used[v]) s.usedVertices[k].push_back(mesh.vertices()[v]);
    }
  }
  // GImpact and compound shapes are shared between the bodies of a kind.
  std::vector<btCollisionShape*> kindShapes;
  for (const auto& k : kinds) {
    if (settings.backend == Backend::Convex) {
      const ConvexDecomposition parts = decompose(k->mesh);
      m_decomposition.hullsPerKind.push_back(parts.hulls.size());
      m_decomposition.volumeRatio.push_back(k->mass.volume > 0 ? parts.hullVolume / k->mass.volume
                                                               : 0.0);
      m_decomposition.hulls += parts.hulls.size();
      m_decomposition.seconds += parts.seconds;
      kindShapes.push_back(s.makeCompound(parts));
    } else if (!adb) {  // adb gives every body its own MeshShape over the shared MeshData
      kindShapes.push_back(s.makeShape(k, false, true));
    }
  }

  std::mt19937_64 rng(settings.seed);
  std::uniform_real_distribution<double> jitter(-0.1, 0.1);
  for (int i = 0; i < settings.bodies; ++i) {
    const int kind = i % kindCount;
    // A 3 x 3 grid per layer, 0.9 apart, layers 0.9 apart, from 1 unit above the floor.
    const int layer = i / 9, cell = i % 9;
    const Vec3 at(-0.9 + 0.9 * (cell % 3) + jitter(rng), 1.0 + 0.9 * layer,
                  -0.9 + 0.9 * (cell / 3) + jitter(rng));
    const Eigen::Quaterniond q = randomRotation(rng);
    const btTransform pose = toBt(Pose{q.toRotationMatrix(), at});
    btCollisionShape* shape = adb ? s.makeShape(kinds[kind], true, true) : kindShapes[kind];
    const Vec3 inertia = kinds[kind]->mass.inertia.diagonal();
    m_dynamic.push_back(s.addBody(shape, 1.0, inertia, pose));
    m_dynamic.back()->setActivationState(DISABLE_DEACTIVATION);  // measure every step
    s.bodyVertices.push_back(&s.usedVertices[static_cast<std::size_t>(kind)]);
    s.bodySize.push_back(kinds[kind]->mesh.bounds().extent().norm());
    s.bodyTree.push_back(&kinds[kind]->tree);
    m_triangles += kinds[kind]->mesh.triangleCount();
  }
}

PileScene::~PileScene() = default;

StepStats PileScene::step() {
  Impl& s = *m_impl;
  StepStats st;
  const auto t0 = std::chrono::steady_clock::now();
  s.world->stepSimulation(btScalar(1.0 / 60.0), 0);
  st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (s.adbDispatcher) st.frame = s.adbDispatcher->lastFrameStats();

  for (int m = 0; m < s.dispatcher->getNumManifolds(); ++m) {
    const btPersistentManifold* manifold = s.dispatcher->getManifoldByIndexInternal(m);
    // The bin's parts are the only static objects.
    const bool bin = manifold->getBody0()->isStaticObject() || manifold->getBody1()->isStaticObject();
    double& kindMax = bin ? st.binPenetration : st.bodyPenetration;
    for (int p = 0; p < manifold->getNumContacts(); ++p) {
      ++st.contacts;
      const double depth = -static_cast<double>(manifold->getContactPoint(p).getDistance());
      st.maxPenetration = std::max(st.maxPenetration, depth);
      kindMax = std::max(kindMax, depth);
    }
  }
  st.lowestY = 1e300;
  for (std::size_t i = 0; i < m_dynamic.size(); ++i) {
    const btRigidBody* b = m_dynamic[i];
    const btVector3 v = b->getLinearVelocity();
    const btVector3 w = b->getWorldTransform().getBasis().transpose() * b->getAngularVelocity();
    const btVector3 inertia = b->getLocalInertia();
    const double kinetic = 0.5 * v.length2() + 0.5 * (inertia.x() * w.x() * w.x() +
                                                      inertia.y() * w.y() * w.y() +
                                                      inertia.z() * w.z() * w.z());
    const double y = b->getWorldTransform().getOrigin().y();
    st.kinetic += kinetic;
    st.energy += kinetic + kGravity * (y - kFloorTop);
    st.atRest += v.length() < 0.05 && b->getAngularVelocity().length() < 0.05 ? 1 : 0;
    st.lowestY = std::min(st.lowestY, y);
    const btVector3& c = b->getWorldTransform().getOrigin();
    // A body whose centre is a quarter of its size below the floor's top is going through
    // (a flat torus resting 0.1 into the floor has its centre at its top).
    const double margin = 0.25 * s.bodySize[i];
    const bool inBin = c.y() > kFloorTop - margin && std::abs(c.x()) < kBinInside + margin &&
                       std::abs(c.z()) < kBinInside + margin;
    st.lost += inBin ? 0 : 1;
    // The lowest vertex: world y = row 1 of the basis . vertex + origin y. Bodies above the
    // floor by more than their size cannot reach it.
    if (y - kFloorTop < s.bodySize[i]) {
      const btVector3 row = b->getWorldTransform().getBasis().getRow(1);
      const Vec3 r(row.x(), row.y(), row.z());
      double lowest = 1e300;
      for (const Vec3& x : *s.bodyVertices[i]) lowest = std::min(lowest, r.dot(x));
      const double depth = std::max(0.0, kFloorTop - (lowest + y));
      st.floorPenetration = std::max(st.floorPenetration, depth);
      st.floorPenetrationRelative = std::max(st.floorPenetrationRelative, depth / s.bodySize[i]);
    }
  }
  return st;
}

void PileScene::probe(StepStats& stats) const {
  const Impl& s = *m_impl;
  std::vector<ProbeBody> bodies;
  bodies.reserve(m_dynamic.size());
  for (std::size_t i = 0; i < m_dynamic.size(); ++i) {
    const btTransform& t = m_dynamic[i]->getWorldTransform();
    Pose pose;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) pose.rotation(r, c) = t.getBasis()[r][c];
      pose.translation[r] = t.getOrigin()[r];
    }
    bodies.push_back(ProbeBody{s.bodyTree[i], s.bodyVertices[i], pose});
  }
  const PenetrationReport report = measurePenetration(bodies);
  stats.probedDepth = report.depth;
  stats.probedRelative = report.relative;
  stats.probedMean = report.meanDepth;
}

}  // namespace adb::demo

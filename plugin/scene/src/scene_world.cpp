#include "adb/scene/scene_world.h"

#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>

#include "adb/bullet/dispatcher.h"
#include "adb/bullet/registration.h"
#include "adb/scene/penetration_probe.h"
#include "body_shapes.h"
#include "adb/bullet/conversions.h"
#include "kinematic_path.h"
#include "overlap_queries.h"
#include "world_measures.h"

namespace adb::scene {

const char* toString(Backend backend) {
  switch (backend) {
    case Backend::Adb: return "adb";
    case Backend::Exact: return "exact";
    case Backend::GImpact: return "gimpact";
    case Backend::Convex: return "convex";
  }
  return "?";
}

Backend parseBackend(const std::string& name) {
  if (name == "adb") return Backend::Adb;
  if (name == "exact") return Backend::Exact;
  if (name == "gimpact") return Backend::GImpact;
  if (name == "convex") return Backend::Convex;
  throw std::invalid_argument("unknown backend '" + name + "' (known: adb, exact, gimpact, convex)");
}

std::string BuildReport::describe() const {
  std::string s = dynamicsWorld ? "btDiscreteDynamicsWorld" : "btCollisionWorld";
  s += booleanQueries ? ", boolean queries" : "";
  s += contactGeneration ? ", contact generation" : ", no contacts";
  s += solver ? ", solver" : ", no solver";
  s += rigidBodies ? ", rigid bodies" : ", no rigid bodies";
  if (dynamicsWorld) {
    s += ccd ? ", ccd" : ", no ccd";
    s += sleeping ? ", sleeping" : ", no sleeping";
  }
  s += budget ? ", per-step budget" : ", no budget";
  return s;
}

namespace {

using Clock = std::chrono::steady_clock;


FrameSettings frameSettings(const Scene& scene, Backend backend) {
  FrameSettings f;
  const WorldSpec& w = scene.world;
  if (backend == Backend::Adb) {
    if (w.budget.kind == BudgetSpec::Kind::Micros) f.budgetMicros = w.budget.micros;
    if (w.budget.kind == BudgetSpec::Kind::NodePairs) f.budgetNodePairs = w.budget.nodePairs;
    f.pMin = w.pMin;
    f.kMin = w.kMin;
    f.pAccept = w.pAccept;
  }
  f.fronts = w.fronts;
  f.threads = w.threads;
  f.keepRestingContacts = w.keepRestingContacts;
  f.auditContacts = w.auditContacts;
  f.softenPlausible = scene.effects.softContacts;
  return f;
}

// The vertices the triangles use.
std::vector<Vec3> verticesInUse(const TriangleMesh& mesh) {
  std::vector<bool> used(mesh.vertices().size(), false);
  for (const Triangle& t : mesh.triangles()) {
    for (std::uint32_t v : t) used[v] = true;
  }
  std::vector<Vec3> out;
  for (std::size_t v = 0; v < used.size(); ++v) {
    if (used[v]) out.push_back(mesh.vertices()[v]);
  }
  return out;
}

// The radius of a sphere inside the body, for Bullet's swept-sphere CCD: a fifth of the
// smallest extent of its box keeps the sphere inside most shapes.
double innerRadius(const TriangleMesh& display) {
  return 0.2 * display.bounds().extent().minCoeff();
}

// GImpact's own registration covers contacts only; contactPairTest (an overlap scene's pair
// test) asks for closest points, which would otherwise find no algorithm for GImpact shapes.
void registerGImpact(btCollisionDispatcher& dispatcher) {
  btGImpactCollisionAlgorithm::registerAlgorithm(&dispatcher);
  static btGImpactCollisionAlgorithm::CreateFunc closestPoints;
  for (int other = 0; other < MAX_BROADPHASE_COLLISION_TYPES; ++other) {
    dispatcher.registerClosestPointsCreateFunc(GIMPACT_SHAPE_PROXYTYPE, other, &closestPoints);
    dispatcher.registerClosestPointsCreateFunc(other, GIMPACT_SHAPE_PROXYTYPE, &closestPoints);
  }
}

// The share of the step's budget the dispatcher's pairs used.
double budgetUse(const BudgetSpec& budget, const FrameStats& frame) {
  if (budget.kind == BudgetSpec::Kind::Micros) {
    return budget.micros > 0 ? frame.micros / budget.micros : 0.0;
  }
  return budget.nodePairs > 0
             ? static_cast<double>(frame.nodePairs) / static_cast<double>(budget.nodePairs)
             : 0.0;
}

}  // namespace

struct SceneWorld::Impl {
  Scene scene;
  Backend backend;
  BuildReport report;
  std::unique_ptr<btDefaultCollisionConfiguration> configuration;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  Dispatcher* adbDispatcher = nullptr;  // the same, when adb's
  btDbvtBroadphase broadphase;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver;
  std::unique_ptr<btCollisionWorld> world;
  btDiscreteDynamicsWorld* dynamics = nullptr;  // world, when it is one
  std::unique_ptr<detail::BodyShapes> shapes;
  std::unique_ptr<detail::OverlapQueries> overlapQueries;

  // Per body, in scene order.
  std::vector<std::unique_ptr<btCollisionObject>> objects;
  std::vector<std::unique_ptr<btDefaultMotionState>> motionStates;  // kinematic, dynamics
  std::vector<detail::BodyShape> bodyShapes;
  std::vector<std::shared_ptr<const MeshData>> meshes;  // per body, nullptr for primitives
  std::vector<double> bodySize;  // per body, its display mesh's box diagonal
  // Per mesh, the vertices its triangles use (a file may hold others, anywhere): the probe's.
  std::map<const MeshData*, std::vector<Vec3>> usedVertices;
  std::vector<const MotionSpec*> motion;  // per body: its motion, if kinematic with one

  int steps = 0;
  StepRecord record;
  std::vector<ContactPoint> contacts;
  std::vector<CutPair> cutPairs;
  std::vector<OverlapEvent> events;
  std::vector<detail::BodyPair> overlapping, overlappingNow;
  std::vector<OverlapPair> overlapPairs;  // overlapping, with confidence
  std::vector<MeshPairReport> pairReports;

  std::vector<std::unique_ptr<btTypedConstraint>> constraints;

  void buildWorld();
  void hingeToWorld(btRigidBody& body, const BodySpec& spec, const Pose& meshFromShape);
  void addBody(std::size_t i);
  void moveBodies(double time);
  void stepOverlap();
  void stepCollision(double dt);
  void measureBounds(StepRecord& r) const;
  /// Without world.bounds: the height (along -gravity) of the lowest point of any static
  /// body, below which a dynamic body is lost; none without static bodies.
  void findFloor();
  std::optional<double> floorHeight;
  Vec3 up = Vec3::UnitY();
  void measureFall(StepRecord& r) const;
  double time() const { return steps * scene.world.timeStep; }
};

void SceneWorld::Impl::buildWorld() {
  const Effects& effects = scene.effects;
  const bool adbDispatch = usesAdbShapes(backend) && effects.kind != Effects::Kind::Overlap;
  configuration = std::make_unique<btDefaultCollisionConfiguration>(collisionConstructionInfo());
  if (adbDispatch) {
    auto d = std::make_unique<Dispatcher>(configuration.get());
    d->setFrameSettings(frameSettings(scene, backend));
    adbDispatcher = d.get();
    dispatcher = std::move(d);
  } else {
    dispatcher = std::make_unique<btCollisionDispatcher>(configuration.get());
    if (!usesAdbShapes(backend)) {
      registerGImpact(*dispatcher);
    } else {
      registerAlgorithms(*dispatcher, *configuration);  // exact, for the non-mesh pairs
    }
  }
  if (effects.kind == Effects::Kind::Dynamics) {
    solver = std::make_unique<btSequentialImpulseConstraintSolver>();
    auto d = std::make_unique<btDiscreteDynamicsWorld>(dispatcher.get(), &broadphase,
                                                       solver.get(), configuration.get());
    d->setGravity(toBt(scene.world.gravity));
    d->getDispatchInfo().m_useContinuous = effects.ccd;
    dynamics = d.get();
    world = std::move(d);
  } else {
    world = std::make_unique<btCollisionWorld>(dispatcher.get(), &broadphase, configuration.get());
  }
  if (effects.kind == Effects::Kind::Overlap) {
    overlapQueries = std::make_unique<detail::OverlapQueries>(scene, backend);
  }
  report.effects = effects.kind;
  report.dynamicsWorld = dynamics != nullptr;
  report.solver = solver != nullptr;
  report.rigidBodies = dynamics != nullptr;
  report.contactGeneration = effects.kind != Effects::Kind::Overlap;
  report.booleanQueries = effects.kind == Effects::Kind::Overlap;
  report.budget = backend == Backend::Adb && scene.world.budget.kind != BudgetSpec::Kind::None;
  report.ccd = dynamics && effects.ccd;
  report.sleeping = dynamics && effects.sleeping;
}

// The body turns about spec.hinge (world) through the origin of its mesh's frame: in the
// shape's frame that origin is inverse(meshFromShape) applied to zero.
void SceneWorld::Impl::hingeToWorld(btRigidBody& body, const BodySpec& spec,
                                    const Pose& meshFromShape) {
  const Pose shapeFromMesh = meshFromShape.inverse();
  const Vec3 pivot = shapeFromMesh.translation;
  const Vec3 axis = shapeFromMesh.rotation * (spec.pose.rotation.transpose() * spec.hinge);
  constraints.push_back(std::make_unique<btHingeConstraint>(body, toBt(pivot), toBt(axis)));
  dynamics->addConstraint(constraints.back().get(), true);
}

void SceneWorld::Impl::addBody(std::size_t i) {
  const BodySpec& spec = scene.bodies[i];
  const Effects& effects = scene.effects;
  detail::BodyShape shape = shapes->make(spec);
  // A pose that places the centre of mass is the shape's own: nothing to move.
  if (spec.poseOf == BodySpec::PoseOf::CentreOfMass) shape.meshFromShape = Pose{};
  const btTransform at = toBt(spec.pose * shape.meshFromShape);
  const double friction = effects.friction ? spec.friction : 0.0;
  const double restitution = effects.restitution ? spec.restitution : 0.0;
  std::unique_ptr<btCollisionObject> object;
  if (dynamics) {
    const bool dynamic = spec.kind == BodySpec::Kind::Dynamic;
    btVector3 inertia(0, 0, 0);
    if (dynamic) {
      // adb's MeshShape gives the mesh's own inertia for every backend (GImpact's is its box's).
      if (shape.mesh) {
        MeshShape(shape.mesh).calculateLocalInertia(static_cast<btScalar>(spec.mass), inertia);
      } else {
        shape.shape->calculateLocalInertia(static_cast<btScalar>(spec.mass), inertia);
      }
    }
    btRigidBody::btRigidBodyConstructionInfo ci(dynamic ? static_cast<btScalar>(spec.mass) : 0,
                                                nullptr, shape.shape, inertia);
    ci.m_startWorldTransform = at;
    ci.m_friction = static_cast<btScalar>(friction);
    ci.m_restitution = static_cast<btScalar>(restitution);
    if (spec.kind == BodySpec::Kind::Kinematic) {
      motionStates.push_back(std::make_unique<btDefaultMotionState>(at));
      ci.m_motionState = motionStates.back().get();
    }
    auto body = std::make_unique<btRigidBody>(ci);
    if (spec.kind == BodySpec::Kind::Kinematic) {
      body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
      body->setActivationState(DISABLE_DEACTIVATION);
    }
    if (dynamic) {
      body->setLinearVelocity(toBt(spec.velocity));
      body->setAngularVelocity(toBt(spec.angularVelocity));
      if (!effects.sleeping) body->setActivationState(DISABLE_DEACTIVATION);
      if (effects.ccd) {
        const double r = innerRadius(*shape.display);
        body->setCcdMotionThreshold(static_cast<btScalar>(r));
        body->setCcdSweptSphereRadius(static_cast<btScalar>(r));
      }
    }
    body->setUserIndex(static_cast<int>(i));
    dynamics->addRigidBody(body.get());
    if (dynamic && spec.hinge != Vec3::Zero()) hingeToWorld(*body, spec, shape.meshFromShape);
    object = std::move(body);
  } else {
    object = std::make_unique<btCollisionObject>();
    object->setCollisionShape(shape.shape);
    object->setWorldTransform(at);
    object->setFriction(static_cast<btScalar>(friction));
    object->setRestitution(static_cast<btScalar>(restitution));
    object->setUserIndex(static_cast<int>(i));
    const bool fixed = spec.kind == BodySpec::Kind::Static;
    object->setCollisionFlags(fixed ? btCollisionObject::CF_STATIC_OBJECT
                                    : spec.kind == BodySpec::Kind::Kinematic
                                          ? btCollisionObject::CF_KINEMATIC_OBJECT
                                          : 0);
    // As btDiscreteDynamicsWorld does: static bodies are not tested against each other.
    const int group = fixed ? btBroadphaseProxy::StaticFilter : btBroadphaseProxy::DefaultFilter;
    const int mask = fixed ? btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter
                           : btBroadphaseProxy::AllFilter;
    world->addCollisionObject(object.get(), group, mask);
  }
  report.meshBodies += shape.mesh ? 1 : 0;
  if (shape.mesh && !usedVertices.count(shape.mesh.get())) {
    usedVertices.emplace(shape.mesh.get(), verticesInUse(shape.mesh->mesh));
  }
  bodySize.push_back(shape.display->bounds().extent().norm());
  meshes.push_back(shape.mesh);
  bodyShapes.push_back(shape);
  objects.push_back(std::move(object));
}

// Kinematic bodies to their motion's pose at `time`; outside dynamics, also the bodies given
// a velocity (they keep it: nothing responds).
void SceneWorld::Impl::moveBodies(double t) {
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const BodySpec& spec = scene.bodies[i];
    Pose pose;
    if (motion[i]) {
      pose = detail::motionPose(spec.pose, *motion[i], t);
    } else if (!dynamics && (spec.velocity != Vec3::Zero() || spec.angularVelocity != Vec3::Zero())) {
      pose = detail::twistPose(spec.pose, spec.velocity, spec.angularVelocity, t);
    } else {
      continue;
    }
    const btTransform at = toBt(pose * bodyShapes[i].meshFromShape);
    auto* rigid = btRigidBody::upcast(objects[i].get());
    if (rigid && rigid->getMotionState()) {
      rigid->getMotionState()->setWorldTransform(at);  // Bullet derives the velocity from it
    } else {
      objects[i]->setWorldTransform(at);
    }
  }
}

void SceneWorld::Impl::stepOverlap() {
  world->updateAabbs();
  world->computeOverlappingPairs();
  overlapQueries->run(*world, meshes, record);
  overlappingNow.clear();
  overlapPairs.clear();
  for (const detail::PairAnswer& a : overlapQueries->answers()) {
    if (!a.overlap) continue;
    overlappingNow.push_back(a.bodies);
    overlapPairs.push_back(OverlapPair{a.bodies.first, a.bodies.second, a.confidence});
  }
  // Answers come sorted by pair (OverlapQueries::run): so are these.
  const auto& answers = overlapQueries->answers();
  events.clear();
  detail::overlapEvents(overlapping, overlappingNow, steps, time(),
                        [&](const detail::BodyPair& p) {
                          for (const detail::PairAnswer& a : answers) {
                            if (a.bodies == p) return a.confidence;
                          }
                          return 1.0;  // the boxes parted: certain
                        },
                        events);
  overlapping.swap(overlappingNow);
  record.overlapping = static_cast<std::uint32_t>(overlapping.size());
  record.events = static_cast<std::uint32_t>(events.size());
}

void SceneWorld::Impl::stepCollision(double dt) {
  const int substeps = std::max(1, scene.world.substeps);
  const double h = dt / substeps;
  for (int k = 1; k <= substeps; ++k) {
    moveBodies(time() - dt + h * k);
    if (dynamics) {
      // One internal step of h: kinematic bodies move within it, at the velocity Bullet
      // derives from their motion states.
      dynamics->stepSimulation(static_cast<btScalar>(h), 0);
    } else {
      world->performDiscreteCollisionDetection();
    }
  }
}

// Against world.bounds: the dynamic bodies lost (their centre out by more than a quarter of
// their size: a body resting deep in a floor has its centre above the floor's top), and how
// far any mesh body's vertex reaches out (into a bin's floor or walls), from the geometry.
void SceneWorld::Impl::measureBounds(StepRecord& r) const {
  if (!dynamics) return;
  if (!scene.world.bounds) {
    measureFall(r);
    return;
  }
  const Aabb& bounds = *scene.world.bounds;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    if (scene.bodies[i].kind != BodySpec::Kind::Dynamic) continue;
    const Pose pose = toPose(objects[i]->getWorldTransform());
    const Vec3& c = pose.translation;
    const Vec3 margin = Vec3::Constant(0.25 * bodySize[i]);
    const bool inside = (c.array() >= (bounds.lo - margin).array()).all() &&
                        (c.array() <= (bounds.hi + margin).array()).all();
    r.lost += inside ? 0 : 1;
    // A body farther inside than its size cannot reach out.
    const Vec3 room = (c - bounds.lo).cwiseMin(bounds.hi - c);
    if (!meshes[i] || room.minCoeff() > bodySize[i]) continue;
    double out = 0.0;
    for (const Vec3& x : usedVertices.at(meshes[i].get())) {
      const Vec3 w = pose.apply(x);
      out = std::max({out, (bounds.lo - w).maxCoeff(), (w - bounds.hi).maxCoeff()});
    }
    r.outOfBounds = std::max(r.outOfBounds, out);
    if (bodySize[i] > 0) r.outOfBoundsRelative = std::max(r.outOfBoundsRelative, out / bodySize[i]);
  }
}

void SceneWorld::Impl::findFloor() {
  const double g = scene.world.gravity.norm();
  if (g > 0.0 && std::isfinite(g)) up = -scene.world.gravity / g;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    if (scene.bodies[i].kind != BodySpec::Kind::Static) continue;
    const Pose pose = toPose(objects[i]->getWorldTransform());
    for (const Vec3& x : bodyShapes[i].display->vertices()) {
      const double h = up.dot(pose.apply(x));
      if (!floorHeight || h < *floorHeight) floorHeight = h;
    }
  }
}

// A scene without bounds: a dynamic body whose centre fell below the lowest static body by
// more than its size went through the floor (it would otherwise count as present for ever,
// falling).
void SceneWorld::Impl::measureFall(StepRecord& r) const {
  if (!floorHeight) return;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    if (scene.bodies[i].kind != BodySpec::Kind::Dynamic) continue;
    const double h = up.dot(toPose(objects[i]->getWorldTransform()).translation);
    r.lost += h < *floorHeight - bodySize[i] ? 1 : 0;
  }
}

SceneWorld::SceneWorld(Scene scene, Backend backend, ConvexShapeMaker convex)
    : m_impl(std::make_unique<Impl>()) {
  if (backend == Backend::Convex && !convex) {
    throw std::invalid_argument("the convex backend needs a shape maker (ConvexShapeMaker)");
  }
  Impl& s = *m_impl;
  const Clock::time_point start = Clock::now();
  s.scene = std::move(scene);
  s.backend = backend;
  s.buildWorld();
  s.shapes = std::make_unique<detail::BodyShapes>(s.scene, backend, std::move(convex));
  s.motion.assign(s.scene.bodies.size(), nullptr);
  for (const MotionSpec& m : s.scene.motions) s.motion[m.body] = &m;
  for (std::size_t i = 0; i < s.scene.bodies.size(); ++i) s.addBody(i);
  if (!s.scene.world.bounds) s.findFloor();
  s.report.bodies = static_cast<int>(s.objects.size());
  s.report.triangles = s.shapes->triangles();
  s.report.buildSeconds = std::chrono::duration<double>(Clock::now() - start).count();
}

SceneWorld::~SceneWorld() {
  Impl& s = *m_impl;
  if (!s.world) return;
  for (auto& c : s.constraints) s.dynamics->removeConstraint(c.get());
  for (auto& o : s.objects) {
    if (auto* rigid = btRigidBody::upcast(o.get()); rigid && s.dynamics) {
      s.dynamics->removeRigidBody(rigid);
    } else {
      s.world->removeCollisionObject(o.get());
    }
  }
}

const StepRecord& SceneWorld::step() {
  Impl& s = *m_impl;
  const double dt = s.scene.world.timeStep;
  ++s.steps;
  s.record = StepRecord{};
  s.record.step = s.steps;
  s.record.time = s.time();
  const Clock::time_point start = Clock::now();
  if (s.overlapQueries) {
    s.moveBodies(s.time());
    s.stepOverlap();
  } else {
    s.stepCollision(dt);
  }
  s.record.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (!s.overlapQueries) {
    detail::measureContacts(*s.dispatcher, s.adbDispatcher, s.pairReports, s.record, s.contacts,
                            s.cutPairs);
    if (s.report.budget) s.record.budgetUse = budgetUse(s.scene.world.budget, s.record.frame);
    // The contact audit is a measurement, not part of the step (it ran inside it).
    s.record.seconds = std::max(0.0, s.record.seconds - 1e-6 * s.record.frame.audit.micros);
  }
  if (s.dynamics) detail::measureDynamics(*s.dynamics, s.scene.world.gravity, s.record);
  s.measureBounds(s.record);
  return s.record;
}

const StepRecord& SceneWorld::last() const { return m_impl->record; }
const Scene& SceneWorld::scene() const { return m_impl->scene; }
Backend SceneWorld::backend() const { return m_impl->backend; }
const BuildReport& SceneWorld::built() const { return m_impl->report; }
std::size_t SceneWorld::bodyCount() const { return m_impl->objects.size(); }

const TriangleMesh& SceneWorld::displayMesh(std::size_t body) const {
  return *m_impl->bodyShapes.at(body).display;
}

Pose SceneWorld::bodyPose(std::size_t body) const {
  return toPose(m_impl->objects.at(body)->getWorldTransform());
}

Pose SceneWorld::scenePose(std::size_t body) const {
  return bodyPose(body) * m_impl->bodyShapes.at(body).meshFromShape.inverse();
}

bool SceneWorld::isDynamic(std::size_t body) const {
  return m_impl->scene.bodies.at(body).kind == BodySpec::Kind::Dynamic;
}

const std::vector<ContactPoint>& SceneWorld::contacts() const { return m_impl->contacts; }
const std::vector<CutPair>& SceneWorld::cutPairs() const { return m_impl->cutPairs; }
const std::vector<OverlapEvent>& SceneWorld::events() const { return m_impl->events; }
const std::vector<OverlapPair>& SceneWorld::overlapping() const { return m_impl->overlapPairs; }

PenetrationReport SceneWorld::probePenetration() const {
  const Impl& s = *m_impl;
  std::vector<ProbeBody> bodies;
  for (std::size_t i = 0; i < s.objects.size(); ++i) {
    if (!s.meshes[i] || !isDynamic(i)) continue;
    bodies.push_back(ProbeBody{&s.meshes[i]->tree, &s.usedVertices.at(s.meshes[i].get()),
                               bodyPose(i)});
  }
  return measurePenetration(bodies);
}

btCollisionWorld& SceneWorld::collisionWorld() { return *m_impl->world; }
btDiscreteDynamicsWorld* SceneWorld::dynamicsWorld() { return m_impl->dynamics; }

}  // namespace adb::scene

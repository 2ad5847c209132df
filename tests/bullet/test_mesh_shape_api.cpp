// MeshShape's API guarantees: the principal frame and its offset back to the mesh, the
// inertia warning, setLocalScaling's strong guarantee, and serialization through Bullet's
// btDefaultSerializer read back by adb::loadMeshShapes.
#include <btBulletCollisionCommon.h>
#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <string>
#include <vector>

#include "adb/bullet/registration.h"
#include "adb/bullet/mesh_serialization.h"
#include "adb/bullet/mesh_shape.h"
#include "adb/bullet/warnings.h"
#include "adb/support/benchmark_poses.h"
#include "adb/support/mesh_generators.h"

namespace adb {
namespace {

constexpr std::uint64_t kSeed = 20261122;
// Moving a vertex to the principal frame and back is two rotations and two translations in
// double: a few ulps of the largest coordinate, far below this.
constexpr double kRoundTrip = 1e-9;
// Bullet may be single precision: inertia of size ~1 carries ~1e-7 relative rounding.
const double kBtTolerance = sizeof(btScalar) == sizeof(float) ? 1e-5 : 1e-12;

btVector3 bt(const Vec3& v) {
  return btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()),
                   static_cast<btScalar>(v.z()));
}

// A closed mesh with no symmetry, off the origin and turned: a box with a sphere stuck to one
// corner, rotated and moved by a random pose.
TriangleMesh asymmetricMesh() {
  std::mt19937_64 rng(kSeed);
  const TriangleMesh box = gen::makeBox(Vec3(1.0, 0.6, 0.3), 2);
  const TriangleMesh ball = gen::transformed(gen::makeSphere(0.4, 2),
                                             Pose{Mat3::Identity(), Vec3(0.9, 0.5, -0.2)});
  const Pose pose = Pose::fromQuaternion(randomRotation(rng), Vec3(12.0, -7.0, 3.5));
  return gen::transformed(gen::merge({box, ball}, "box-and-ball"), pose);
}

TEST(MeshShapeApi, DefaultFrameIsTheMeshsOwn) {
  const TriangleMesh mesh = asymmetricMesh();
  const auto data = MeshData::build(mesh);
  EXPECT_EQ(data->mesh.vertices(), mesh.vertices());
  EXPECT_EQ(data->meshFromShape.rotation, Mat3::Identity());
  EXPECT_EQ(data->meshFromShape.translation, Vec3::Zero());
}

TEST(MeshShapeApi, PrincipalFrameMapsBackToTheOriginalMeshExactly) {
  const TriangleMesh mesh = asymmetricMesh();
  const auto original = MeshData::build(mesh);
  const auto data = MeshData::build(mesh, {}, ShapeFrame::Principal);
  const Pose& back = data->meshFromShape;

  // A proper rotation: orthonormal, det +1 (a reflection would turn the mesh inside out).
  EXPECT_NEAR((back.rotation.transpose() * back.rotation - Mat3::Identity()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(back.rotation.determinant(), 1.0, 1e-12);
  EXPECT_EQ(data->facing, original->facing);
  EXPECT_EQ(data->facing, 1);

  // meshFromShape takes every principal-frame vertex back onto the original one.
  ASSERT_EQ(data->mesh.vertices().size(), mesh.vertices().size());
  EXPECT_EQ(data->mesh.triangles(), mesh.triangles());
  double largest = 0.0;
  for (const Vec3& v : mesh.vertices()) largest = std::max(largest, v.norm());
  for (std::size_t i = 0; i < mesh.vertices().size(); ++i) {
    const Vec3 mapped = back.rotation * data->mesh.vertices()[i] + back.translation;
    ASSERT_LE((mapped - mesh.vertices()[i]).norm(), kRoundTrip * largest) << "vertex " << i;
  }

  // The moved mesh really is in its principal frame: recomputed from scratch, its centre of
  // mass is the origin and its tensor diagonal, with the original's moments.
  const MassProperties again = computeMassProperties(data->mesh);
  const double size = data->mesh.bounds().extent().norm();
  const double moment = original->mass.principalMoments.maxCoeff();
  EXPECT_LE(again.centerOfMass.norm(), kRoundTrip * size);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      const double expected = r == c ? original->mass.principalMoments[r] : 0.0;
      EXPECT_NEAR(again.inertia(r, c), expected, kRoundTrip * moment) << r << ", " << c;
    }
  }
  EXPECT_NEAR(data->mass.volume, original->mass.volume, kRoundTrip * original->mass.volume);
  // The frame off the origin was not a principal frame: the test means something.
  EXPECT_GT(original->mass.centerOfMass.norm(), 1.0);

  // calculateLocalInertia is the principal moments; principalTransform the identity.
  MeshShape shape(data);
  btVector3 inertia;
  shape.calculateLocalInertia(2, inertia);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(inertia[k], 2 * original->mass.principalMoments[k], kBtTolerance * moment);
  }
  const btTransform p = shape.principalTransform();
  EXPECT_NEAR(p.getOrigin().length(), 0.0, kBtTolerance);
  EXPECT_NEAR((p.getBasis().getRow(0) - btVector3(1, 0, 0)).length(), 0.0, kBtTolerance);
  EXPECT_NEAR((p.getBasis().getRow(1) - btVector3(0, 1, 0)).length(), 0.0, kBtTolerance);
}

TEST(MeshShapeApi, ScaledCopyKeepsTheOffsetToTheMesh) {
  const auto data = MeshData::build(asymmetricMesh(), {}, ShapeFrame::Principal);
  MeshShape shape(data);
  shape.setLocalScaling(btVector3(2, 0.5, 1.5));
  ASSERT_NE(&shape.data(), data.get());
  EXPECT_EQ(shape.data().meshFromShape.rotation, data->meshFromShape.rotation);
  EXPECT_EQ(shape.data().meshFromShape.translation, data->meshFromShape.translation);
}

std::vector<std::string> g_warnings;
void collectWarning(const char* message) { g_warnings.emplace_back(message); }

// Installs the collecting handler for one test and restores the previous one after.
struct CollectWarnings {
  WarningHandler previous;
  CollectWarnings() : previous(setWarningHandler(&collectWarning)) { g_warnings.clear(); }
  ~CollectWarnings() { setWarningHandler(previous); }
};

TEST(MeshShapeApi, InertiaOffThePrincipalFrameWarnsOncePerMeshData) {
  const CollectWarnings collect;
  const auto meshFrame = MeshData::build(asymmetricMesh());
  MeshShape a(meshFrame), b(meshFrame);
  btVector3 inertia;
  a.calculateLocalInertia(1, inertia);
  a.calculateLocalInertia(1, inertia);
  b.calculateLocalInertia(1, inertia);
  ASSERT_EQ(g_warnings.size(), 1u);
  EXPECT_NE(g_warnings[0].find("box-and-ball"), std::string::npos) << g_warnings[0];
  EXPECT_NE(g_warnings[0].find("ShapeFrame::Principal"), std::string::npos) << g_warnings[0];

  // Another MeshData of the same mesh warns again: the flag belongs to the data.
  MeshShape c(MeshData::build(asymmetricMesh()));
  c.calculateLocalInertia(1, inertia);
  EXPECT_EQ(g_warnings.size(), 2u);
}

TEST(MeshShapeApi, InertiaInThePrincipalFrameDoesNotWarn) {
  const CollectWarnings collect;
  btVector3 inertia;
  MeshShape principal(MeshData::build(asymmetricMesh(), {}, ShapeFrame::Principal));
  principal.calculateLocalInertia(1, inertia);
  // Scaling along the principal axes keeps them principal (its tree and mass are recomputed:
  // rounding only, well inside the tolerance).
  principal.setLocalScaling(btVector3(3, 0.5, 1.25));
  principal.calculateLocalInertia(1, inertia);
  // A mesh built around its centre of mass along its axes needs no option.
  MeshShape box(MeshData::build(gen::makeBox(Vec3(1, 2, 3), 2)));
  box.calculateLocalInertia(1, inertia);
  EXPECT_TRUE(g_warnings.empty()) << g_warnings.front();
}

TEST(MeshShapeApi, FailedSetLocalScalingChangesNothing) {
  const auto data = MeshData::build(gen::makeBox(Vec3(1, 1, 1), 2));
  MeshShape shape(data);
  // Representable in float Bullet too; the scaled mesh, 2e13 across, is beyond what a tree
  // holds (1e12), so the build throws.
  const btVector3 tooLarge(btScalar(1e13), 1, 1);
  for (const btVector3& before : {btVector3(1, 1, 1), btVector3(2, 0.5, 1)}) {
    shape.setLocalScaling(before);
    const AdbTree* tree = &shape.tree();
    const MeshData* d = &shape.data();
    EXPECT_THROW(shape.setLocalScaling(tooLarge), MeshError);
    EXPECT_EQ(shape.getLocalScaling(), before);
    EXPECT_EQ(&shape.tree(), tree);
    EXPECT_EQ(&shape.data(), d);
  }
}

// --- serialization ------------------------------------------------------------------------

// A collision world with adb's algorithms on Bullet's own dispatcher (exact contacts), owning
// its objects.
struct CollisionWorld {
  btDefaultCollisionConfiguration configuration{collisionConstructionInfo()};
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btCollisionWorld world{&dispatcher, &broadphase, &configuration};
  std::vector<std::unique_ptr<btCollisionObject>> objects;

  CollisionWorld() { registerAlgorithms(dispatcher, configuration); }
  ~CollisionWorld() {
    for (auto& o : objects) world.removeCollisionObject(o.get());
  }
  void add(btCollisionShape* shape, const btTransform& at) {
    auto o = std::make_unique<btCollisionObject>();
    o->setCollisionShape(shape);
    o->setWorldTransform(at);
    o->setUserIndex(static_cast<int>(objects.size()));
    world.addCollisionObject(o.get());
    objects.push_back(std::move(o));
  }

  struct Contact {
    int a, b;
    btVector3 onB, normal;
    btScalar distance;
  };
  std::vector<Contact> contacts() {
    world.performDiscreteCollisionDetection();
    std::vector<Contact> out;
    for (int m = 0; m < dispatcher.getNumManifolds(); ++m) {
      const btPersistentManifold* pm = dispatcher.getManifoldByIndexInternal(m);
      for (int c = 0; c < pm->getNumContacts(); ++c) {
        const btManifoldPoint& p = pm->getContactPoint(c);
        out.push_back({pm->getBody0()->getUserIndex(), pm->getBody1()->getUserIndex(),
                       p.m_positionWorldOnB, p.m_normalWorldOnB, p.getDistance()});
      }
    }
    return out;
  }
};

std::vector<unsigned char> bufferOf(const btDefaultSerializer& s) {
  return std::vector<unsigned char>(s.getBufferPointer(),
                                    s.getBufferPointer() + s.getCurrentBufferSize());
}

void expectSameMesh(const MeshShape& loaded, const MeshShape& original) {
  // The unscaled shared meshes, and the scaled ones the queries run on.
  EXPECT_EQ(loaded.getLocalScaling(), original.getLocalScaling());
  EXPECT_EQ(loaded.getMargin(), original.getMargin());
  EXPECT_EQ(loaded.data().mesh.vertices(), original.data().mesh.vertices());
  EXPECT_EQ(loaded.data().mesh.triangles(), original.data().mesh.triangles());
}

TEST(MeshShapeApi, SerializedShapeReadsBackWithItsMeshScalingAndName) {
  MeshShape shape(MeshData::build(gen::makeModel("knot", 1500), {}, ShapeFrame::Principal));
  shape.setLocalScaling(btVector3(1.5, 0.75, 2));  // float-representable: Bullet stores float
  shape.setMargin(btScalar(0.0625));
  btDefaultSerializer serializer;
  serializer.registerNameForPointer(&shape, "the knot");
  serializer.startSerialization();
  shape.serializeSingleShape(&serializer);
  serializer.finishSerialization();
  const std::vector<unsigned char> buffer = bufferOf(serializer);

  const std::vector<LoadedMeshShape> loaded = loadMeshShapes(buffer.data(), buffer.size());
  ASSERT_EQ(loaded.size(), 1u);
  EXPECT_EQ(loaded[0].name, "the knot");
  expectSameMesh(*loaded[0].shape, shape);
  EXPECT_EQ(loaded[0].shape->getShapeType(), CUSTOM_CONCAVE_SHAPE_TYPE);
}

TEST(MeshShapeApi, SerializedWorldReadsBackAndCollidesTheSame) {
  const auto knot = MeshData::build(gen::makeModel("knot", 2000));
  const auto torus = MeshData::build(gen::makeTorus(0.35, 0.12, 48, 24));
  MeshShape a(knot), b(torus), c(torus), d(knot);
  b.setLocalScaling(btVector3(1.5, 1.5, 0.5));
  btBoxShape box(btVector3(btScalar(0.3), btScalar(0.2), btScalar(0.1)));
  std::mt19937_64 rng(kSeed);
  std::vector<btTransform> at;
  for (int i = 0; i < 5; ++i) {
    const Eigen::Quaterniond q = randomRotation(rng);
    at.emplace_back(btQuaternion(static_cast<btScalar>(q.x()), static_cast<btScalar>(q.y()),
                                 static_cast<btScalar>(q.z()), static_cast<btScalar>(q.w())),
                    btVector3(btScalar(0.1) * static_cast<btScalar>(i), 0, 0));
  }
  CollisionWorld original;
  original.add(&a, at[0]);
  original.add(&b, at[1]);
  original.add(&c, at[2]);
  original.add(&d, at[3]);
  original.add(&box, at[4]);

  btDefaultSerializer serializer;
  original.world.serialize(&serializer);
  const std::vector<unsigned char> buffer = bufferOf(serializer);
  const std::vector<LoadedMeshShape> loaded = loadMeshShapes(buffer.data(), buffer.size());

  // The mesh shapes in the order the world holds them (the box is not a mesh: skipped).
  ASSERT_EQ(loaded.size(), 4u);
  expectSameMesh(*loaded[0].shape, a);
  expectSameMesh(*loaded[1].shape, b);
  expectSameMesh(*loaded[2].shape, c);
  expectSameMesh(*loaded[3].shape, d);
  // a and d shared one MeshData when written: so do they when read.
  EXPECT_EQ(&loaded[0].shape->data(), &loaded[3].shape->data());
  EXPECT_NE(&loaded[0].shape->data(), &loaded[2].shape->data());

  CollisionWorld restored;
  restored.add(loaded[0].shape.get(), at[0]);
  restored.add(loaded[1].shape.get(), at[1]);
  restored.add(loaded[2].shape.get(), at[2]);
  restored.add(loaded[3].shape.get(), at[3]);
  restored.add(&box, at[4]);
  const auto expected = original.contacts();
  const auto got = restored.contacts();
  ASSERT_GT(expected.size(), 10u);  // the bodies overlap: the comparison means something
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].a, expected[i].a);
    EXPECT_EQ(got[i].b, expected[i].b);
    EXPECT_EQ(got[i].onB, expected[i].onB) << "contact " << i;
    EXPECT_EQ(got[i].normal, expected[i].normal) << "contact " << i;
    EXPECT_EQ(got[i].distance, expected[i].distance) << "contact " << i;
  }
}

TEST(MeshShapeApi, MeshShapeInACompoundIsSerializedToo) {
  MeshShape mesh(MeshData::build(gen::makeModel("gears", 1000)));
  btCompoundShape compound;
  compound.addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(1, 2, 3)), &mesh);
  btDefaultSerializer serializer;
  serializer.startSerialization();
  compound.serializeSingleShape(&serializer);
  serializer.finishSerialization();
  const std::vector<unsigned char> buffer = bufferOf(serializer);
  const std::vector<LoadedMeshShape> loaded = loadMeshShapes(buffer.data(), buffer.size());
  ASSERT_EQ(loaded.size(), 1u);
  expectSameMesh(*loaded[0].shape, mesh);
}

TEST(MeshShapeApi, BulletsOwnTriangleMeshShapeLoadsAsAMeshShape) {
  // Two parts with float or double vertices (btTriangleMesh stores btScalar) and 32-bit
  // indices, as Bullet writes them: the loader is not limited to what adb writes.
  const TriangleMesh source = gen::makeTorus(0.5, 0.2, 16, 8);
  btTriangleMesh triangles;
  for (const Triangle& t : source.triangles()) {
    triangles.addTriangle(bt(source.vertices()[t[0]]), bt(source.vertices()[t[1]]),
                          bt(source.vertices()[t[2]]), true);
  }
  btBvhTriangleMeshShape shape(&triangles, true);
  shape.setLocalScaling(btVector3(2, 2, 2));
  btDefaultSerializer serializer;
  serializer.startSerialization();
  shape.serializeSingleShape(&serializer);
  serializer.finishSerialization();
  const std::vector<unsigned char> buffer = bufferOf(serializer);
  const std::vector<LoadedMeshShape> loaded = loadMeshShapes(buffer.data(), buffer.size());
  ASSERT_EQ(loaded.size(), 1u);
  EXPECT_EQ(loaded[0].shape->getLocalScaling(), btVector3(2, 2, 2));
  // Same triangles, corner for corner (welded by btTriangleMesh, so compared by position).
  const TriangleMesh& mesh = loaded[0].shape->data().mesh;  // scaled by 2: exact
  ASSERT_EQ(mesh.triangleCount(), source.triangleCount());
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const btVector3 expected = btScalar(2) * bt(source.vertices()[source.triangles()[t][k]]);
      ASSERT_EQ(bt(mesh.vertices()[mesh.triangles()[t][k]]), expected) << t << ", " << k;
    }
  }
}

TEST(MeshShapeApi, MalformedBuffersThrowMeshError) {
  MeshShape shape(MeshData::build(gen::makeBox(Vec3(1, 1, 1), 1)));
  btDefaultSerializer serializer;
  serializer.startSerialization();
  shape.serializeSingleShape(&serializer);
  serializer.finishSerialization();
  std::vector<unsigned char> buffer = bufferOf(serializer);
  EXPECT_NO_THROW(loadMeshShapes(buffer.data(), buffer.size()));
  // Truncated anywhere: a chunk past the end.
  for (std::size_t cut : {std::size_t{5}, std::size_t{20}, buffer.size() / 2, buffer.size() - 1}) {
    EXPECT_THROW(loadMeshShapes(buffer.data(), cut), MeshError) << "cut at " << cut;
  }
  // Not a Bullet buffer.
  const char junk[] = "NOT A BULLET FILE AT ALL";
  EXPECT_THROW(loadMeshShapes(junk, sizeof(junk)), MeshError);
  EXPECT_THROW(loadMeshShapes(nullptr, 0), MeshError);
}

}  // namespace
}  // namespace adb

namespace adb {
namespace {

// The winding's sign is read per connected part: all outward 1, all inward -1, both 0
// (two-sided: a room's inward shell holding outward furniture).
TEST(MeshShapeApi, PartsWoundBothWaysMakeATwoSidedMesh) {
  const TriangleMesh box = gen::makeBox(Vec3(1, 1, 1));
  std::vector<Triangle> flipped;
  for (const Triangle& t : box.triangles()) flipped.push_back(Triangle{t[0], t[2], t[1]});
  const TriangleMesh shell(box.vertices(), flipped, "shell");
  const TriangleMesh chair = gen::transformed(gen::makeBox(Vec3(0.2, 0.2, 0.2)),
                                              Pose{Mat3::Identity(), Vec3(0.3, -0.7, 0)});
  EXPECT_EQ(MeshData::build(box)->facing, 1);
  EXPECT_EQ(MeshData::build(shell)->facing, -1);
  EXPECT_EQ(MeshData::build(gen::merge({box, chair}))->facing, 1);
  EXPECT_EQ(MeshData::build(gen::merge({shell, chair}))->facing, 0);
  EXPECT_EQ(MeshData::build(gen::makeRoom())->facing, 0);
}

}  // namespace
}  // namespace adb

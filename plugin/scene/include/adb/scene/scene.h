// A scene as read from a file: the world's settings, named shapes, bodies, kinematic motions
// and the effects the scene asks for. Plain data, validated by the loader (scene_file.h):
// every name referenced exists, every number is in range, every effect has what it needs.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "adb/bullet/frame_budget.h"
#include "adb/core/geometry.h"
#include "adb/core/mesh.h"

namespace adb::scene {

/// The per-step budget for every pair that involves an adb mesh (adb::FrameSettings).
struct BudgetSpec {
  enum class Kind { None, Micros, NodePairs } kind = Kind::None;
  double micros = 0.0;
  std::uint64_t nodePairs = 0;
};

struct WorldSpec {
  Vec3 gravity = Vec3(0, -9.81, 0);
  double timeStep = 1.0 / 60.0;  ///< seconds per step
  int steps = 600;
  int substeps = 1;  ///< Bullet's fixed substeps per step
  BudgetSpec budget;
  double pMin = 0.99;    ///< quality target: probability (with kMin > 0)
  int kMin = 0;          ///< quality target: node pairs above pMin (0: contacts, no target)
  double pAccept = 0.9;  ///< unresolved node pairs at or above this become plausible contacts
  /// Whether mesh-mesh pairs keep their fronts across steps (adb::FrameSettings::fronts).
  adb::FrameSettings::Fronts fronts = adb::FrameSettings::Fronts::WithNodePairBudget;
  /// Threads for adb's pair queries (adb::FrameSettings::threads): 0 all, 1 none.
  int threads = 1;
  /// Pairs at rest keep their contacts (adb::FrameSettings::keepRestingContacts).
  bool keepRestingContacts = true;
  /// Audit plausible contacts against exact ones (adb::FrameSettings::auditContacts).
  bool auditContacts = false;
  /// Where dynamic bodies belong (a bin's inside, say): a body whose centre is outside it by
  /// more than a quarter of its size (its box's diagonal) is lost. None: a body is lost when
  /// its centre falls below the lowest static body by more than its size.
  std::optional<Aabb> bounds;
};

struct ShapeSpec {
  enum class Kind { Mesh, Generated, Box, Sphere, Capsule, Plane } kind = Kind::Box;
  std::string name;
  // Mesh: a file read through adb::io, or a mesh given in code (a scene built in code), then
  // scaled and recentred on its bounding box's centre.
  std::filesystem::path file;  ///< absolute (resolved against the scene file's folder)
  std::shared_ptr<const TriangleMesh> given;  ///< in place of a file when set
  double scale = 1.0;
  bool recentre = true;
  /// > 0: scaled about its box's centre to this largest extent, in place of scale and
  /// recentre (files come in any unit).
  double size = 0.0;
  // Generated: one of generatedModelNames() (scene_models.h), about this many triangles,
  // then scaled. "gear" takes `teeth`; "box" takes halfExtents.
  std::string model;
  std::size_t triangles = 2000;
  int teeth = 12;
  // Primitives (Bullet's shapes).
  Vec3 halfExtents = Vec3::Zero();  ///< box
  double radius = 0.0;              ///< sphere, capsule
  double height = 0.0;              ///< capsule: between the caps' centres, along y
  Vec3 normal = Vec3::UnitY();      ///< plane (unit)
  double offset = 0.0;              ///< plane: normal . x = offset
};

struct BodySpec {
  enum class Kind { Static, Dynamic, Kinematic } kind = Kind::Dynamic;
  std::string name;
  std::size_t shape = 0;  ///< index into Scene::shapes
  double mass = 1.0;      ///< dynamic bodies: > 0
  /// What `pose` places: the mesh's own frame, or (dynamic mesh bodies) its centre of mass
  /// and principal axes, as Bullet's body does.
  enum class PoseOf { Mesh, CentreOfMass } poseOf = PoseOf::Mesh;
  Pose pose;
  Vec3 velocity = Vec3::Zero();
  Vec3 angularVelocity = Vec3::Zero();
  double friction = 0.5;
  double restitution = 0.0;
  /// A dynamic body hinged to the world (a gear on its axle): it turns about this axis (world
  /// frame, unit) through its origin, and nothing else. Zero: free.
  Vec3 hinge = Vec3::Zero();
};

struct Keyframe {
  double time = 0.0;  ///< seconds, increasing
  Pose pose;
};

/// How a kinematic body moves: a constant twist (from its initial pose), or keyframes
/// (interpolated; held after the last).
struct MotionSpec {
  std::size_t body = 0;  ///< index into Scene::bodies, a kinematic body
  bool twist = true;
  Vec3 linear = Vec3::Zero();   ///< twist: m/s, world frame
  Vec3 angular = Vec3::Zero();  ///< twist: rad/s, world frame
  std::vector<Keyframe> keyframes;
};

/// What the scene asks to simulate: one of overlap events, contacts, or dynamics, and within
/// dynamics its extras. The runner builds only what is asked for.
struct Effects {
  enum class Kind { Overlap, Contacts, Dynamics } kind = Kind::Dynamics;
  bool friction = false;
  bool restitution = false;
  bool sleeping = false;
  bool ccd = false;
  bool softContacts = false;  ///< plausible contacts softened by their probability
};

/// Where pictures look from (optional: without it they frame every body as it starts).
struct ViewSpec {
  bool given = false;
  Vec3 eye = Vec3::Zero();
  Vec3 target = Vec3::Zero();
  double fovDegrees = 40.0;
};

struct Scene {
  std::filesystem::path file;  ///< where it was read from (empty when parsed from text)
  std::string description;
  ViewSpec view;
  WorldSpec world;
  std::vector<ShapeSpec> shapes;
  std::vector<BodySpec> bodies;
  std::vector<MotionSpec> motions;
  Effects effects;
};

}  // namespace adb::scene

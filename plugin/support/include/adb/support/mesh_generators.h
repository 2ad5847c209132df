// Generated test geometry (namespace adb::gen): boxes, grids, spheres, tori, knots, gears, pipe
// bundles and a lock assembly, plus the named benchmark models of makeModel(); and meshes shaped
// like real scenes' ones (a sliver cylinder, a furnished room, a robot arm; named models too).
// Nothing is read from files, so tests, demos and benchmarks all see the same meshes on every
// machine.
//
// Conventions shared by every generator:
//  - Closed shapes are watertight by index: every edge is used by exactly two triangles, once in
//    each direction, and triangles wind counter-clockwise seen from outside (outward normals).
//  - Shapes are centred at (or near) the origin; the named models fit in about 2 x 2 x 2 units.
//  - Invalid parameters (non-positive sizes, too few segments, ...) throw adb::MeshError.
//  - No generator emits degenerate triangles for valid parameters.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "adb/core/geometry.h"
#include "adb/core/mesh.h"

namespace adb::gen {

/// Closed box [-halfExtents, halfExtents]; every face is split into subdivisions x subdivisions
/// quads of two triangles. Triangles: 12 * subdivisions^2; vertices: 6 * subdivisions^2 + 2.
TriangleMesh makeBox(const Vec3& halfExtents, int subdivisions = 1);

/// Open, zero-thickness grid in the plane z = 0 covering [-sizeX/2, sizeX/2] x [-sizeY/2, sizeY/2]
/// with nx x ny cells; triangles face +z. Triangles: 2 * nx * ny; vertices: (nx + 1) * (ny + 1).
TriangleMesh makeFlatGrid(double sizeX, double sizeY, int nx, int ny);

/// Closed geodesic icosphere: each edge of an icosahedron is split into `subdivisions` pieces
/// (the "frequency"; 1 gives the icosahedron) and every vertex is pushed onto the sphere.
/// Triangles: 20 * subdivisions^2; vertices: 10 * subdivisions^2 + 2. Unlike recursive
/// subdivision (20 * 4^k) this allows any count, which makeModel() needs.
TriangleMesh makeSphere(double radius, int subdivisions);

/// Closed torus around the z axis: majorSegments around z, minorSegments around the tube.
/// Triangles: 2 * majorSegments * minorSegments.
TriangleMesh makeTorus(double majorRadius, double minorRadius, int majorSegments,
                       int minorSegments);

/// Closed solid cylinder along z, centred at the origin: `segments` around, `heightSegments`
/// along the side and `capRings` concentric rings on each cap (the innermost ring is a fan).
/// Triangles: 2 * segments * (heightSegments + 2 * capRings - 1). Its volume is exactly that of
/// the inscribed prism, 0.5 * segments * radius^2 * sin(2 pi / segments) * height.
TriangleMesh makeCylinder(double radius, double height, int segments, int heightSegments = 1,
                          int capRings = 1);

/// Closed tube of radius `tubeRadius` around the (p, q) torus knot with centre line
///   c(t) = ((R + R/2 cos qt) cos pt, (R + R/2 cos qt) sin pt, R/2 sin qt),  t in [0, 2 pi),
/// R = radius. p and q must be coprime (else the curve is not a single knot). `segments` rings
/// along the curve, `tubeSegments` vertices per ring. Triangles: 2 * segments * tubeSegments.
/// tubeRadius must be below radius / 2; keep it at or below about 0.15 * radius for the common
/// knots ((2,3), (3,2), (2,5), (3,4)) or strands of the tube intersect each other.
TriangleMesh makeTorusKnot(int p, int q, double radius, double tubeRadius, int segments,
                           int tubeSegments);

/// Closed spur gear around the z axis, z in [-thickness/2, thickness/2], with a round bore.
/// Each tooth is a trapezoid between rootRadius and outerRadius (at the root it covers 55 % of
/// the tooth pitch, at the tip 25 %), sampled by segmentsPerTooth (>= 4) angles; the bore wall
/// uses the same angles. The flat faces get radialSegments rings, the outer and bore walls
/// axialSegments layers. The first tooth is centred at angle pi / teeth.
/// Triangles: 4 * teeth * segmentsPerTooth * (radialSegments + axialSegments).
TriangleMesh makeGear(int teeth, double outerRadius, double rootRadius, double boreRadius,
                      double thickness, int segmentsPerTooth, int radialSegments = 1,
                      int axialSegments = 1);

/// Two copies of makeGear(...) side by side, centred at (-d/2, 0, 0) and (d/2, 0, 0) with
/// d = outerRadius + rootRadius + 0.3 * (outerRadius - rootRadius): a tooth of the left gear
/// points into a gap of the right gear, so the teeth interleave without touching. Checked for
/// 3..100 teeth with tooth heights (outerRadius - rootRadius) up to the tooth pitch on the
/// root circle, 2 pi rootRadius / teeth; much taller teeth may collide. The left gear comes
/// first in the vertex and triangle arrays. Triangles: twice those of makeGear().
TriangleMesh makeGearPair(int teeth, double outerRadius, double rootRadius, double boreRadius,
                          double thickness, int segmentsPerTooth, int radialSegments = 1,
                          int axialSegments = 1);

/// Closed bundle of `pipes` hollow pipes (outer and inner wall, annular end caps). Every pipe is
/// a 90-degree bend of centre-line length `length` lying in a horizontal plane; pipe k sits at
/// its own height (layers 2.5 * radius apart, so pipes never touch) and is turned by
/// k * 180 / pipes degrees about z, so the bends criss-cross above the origin: a concave shape.
/// `segments` around each pipe, `lengthSegments` along it.
/// Triangles: 4 * pipes * segments * (lengthSegments + 1).
TriangleMesh makePipeBundle(int pipes, double length, double radius, double wallThickness,
                            int segments, int lengthSegments);

/// A lock-like assembly, about 1.75 x 1.0 x 0.36 units: a housing plate, a bolt (boxes), a plug
/// cylinder, three pin cylinders and two screw heads, merged into one mesh. Each part is closed
/// and outward-facing; parts interpenetrate. `resolution` sets the target edge length
/// (1 / resolution units; every cylinder keeps at least 8 segments), so the triangle count
/// grows roughly with resolution^2 (about 12 * resolution^2 for large resolutions).
TriangleMesh makeLockAssembly(int resolution);

/// Closed cylinder along z, centred at the origin, triangulated the way CAD exporters write
/// one: the side in heightSegments rows of quads split into two triangles, each cap a fan from
/// one rim vertex (no centre vertex). Every triangle is long and thin: the side triangles'
/// aspect (triangleAspect) is about (height / heightSegments) / (2 pi radius / segments), the
/// caps' at least about segments / pi. Triangles: 2 * segments * (heightSegments + 1) - 4.
TriangleMesh makeSliverCylinder(double radius, double height, int segments,
                                int heightSegments = 1);

/// A furnished room in the manner of FCL's test environment (its env.obj: 2,180 triangles,
/// median aspect 125:1): the inside of a 6 x 6 x 3 box centred at the origin (floor at
/// z = -1.5; floor, ceiling and four walls of two large triangles each, wound to face
/// inward) holding furniture of boxes and sliver cylinders: a table and four chairs, a
/// bookshelf, a sofa, a radiator under a window frame, a door frame, skirting boards, two
/// pipes and a lamp under the ceiling. Closed by index (every part is, parts are not welded):
/// the shell faces inward, so the signed volume is negative; each piece of furniture faces
/// outward and stands inside the shell, at least 1 cm from it. Triangles: 1,512 (a fixed
/// resolution); median aspect (triangleAspect) 23, 336 triangles above 100.
TriangleMesh makeRoom();

/// A low-poly robot arm, about 0.8 long (along x), 0.24 wide and 0.6 high, with its bounding
/// box centred at the origin: a base, a turret, shoulder, elbow and wrist joints (cylinders
/// as makeSliverCylinder's), upper arm and forearm links and a two-finger gripper (boxes),
/// bent as if reaching forward and a little down. Each part is closed and outward; parts
/// interpenetrate at the joints, as the lock assembly's do. Triangles: 296 (a fixed
/// resolution).
TriangleMesh makeRobotArm();

/// The named benchmark models: "pipes", "gears", "lock", "knot", "torus", "sphere".
std::vector<std::string> modelNames();

/// Named models with the triangles that real meshes bring (long slivers, large flat
/// triangles) rather than the benchmark shapes' well-shaped ones: "slivers" (a
/// makeSliverCylinder of radius 0.25 and height 1.8 whose side triangles stay about 100:1 at
/// every target; built by makeModel like the models of modelNames()), then the
/// fixedModelNames(). Kept out of modelNames(), whose six shapes the tools and tests iterate
/// over as the paper's benchmark.
std::vector<std::string> realMeshModelNames();

/// The named models with one fixed resolution: "room" (makeRoom) and "robot" (makeRobotArm).
/// Their triangle counts follow no target: makeFixedModel builds them, makeModel does not.
std::vector<std::string> fixedModelNames();

/// The named model (one of modelNames(), or "slivers") at a resolution whose triangle count
/// is within about +-25 % of targetTriangles (checked for targets from 1,000 to 1,000,000;
/// smaller targets get the coarsest sensible mesh, which may be larger). Throws MeshError for
/// an unknown name; the message lists the known names (and names makeFixedModel for a fixed
/// model).
TriangleMesh makeModel(const std::string& name, std::size_t targetTriangles);

/// The named fixed-resolution model (one of fixedModelNames()), named as asked. Throws
/// MeshError for an unknown name; the message lists the known names.
TriangleMesh makeFixedModel(const std::string& name);

/// Any named model: a fixed one (fixedModelNames()) as it is, the others (modelNames(),
/// "slivers") by makeModel at targetTriangles. Throws MeshError for an unknown name.
TriangleMesh makeAnyModel(const std::string& name, std::size_t targetTriangles);

/// The aspect ratio of triangle i of `mesh`: its longest edge over its height onto that edge
/// (longest^2 / (2 area)). 2 / sqrt(3) for an equilateral triangle, about L / w for a sliver L
/// long and w wide; infinity for a degenerate one.
double triangleAspect(const TriangleMesh& mesh, std::size_t i);

/// The median of triangleAspect over the mesh's triangles (the upper median for an even
/// count); 0 for a mesh without triangles.
double medianAspect(const TriangleMesh& mesh);

/// All meshes in one: vertices and triangles concatenated in order (indices offset), nothing
/// welded. Throws MeshError when `meshes` is empty.
TriangleMesh merge(const std::vector<TriangleMesh>& meshes, const std::string& name = "merged");

/// A copy of `mesh` with every vertex mapped by `pose` (rotation * v + translation); same
/// triangles and name. A proper rotation keeps the winding outward.
TriangleMesh transformed(const TriangleMesh& mesh, const Pose& pose);

}  // namespace adb::gen

// AdbTree: the ADB-tree of Klein & Zachmann — a binary AABB tree whose nodes also store the
// number of "possible collision cells" (pc) of their polygons, plus per-node surface
// statistics (area, mean normal, centroid) for plausible contacts.
//
// Built once from a validated TriangleMesh, in coordinates local to the mesh (relative to its
// bounding-box centre, so a mesh 1e5 units from the origin keeps its precision). Immutable
// after construction: any number of threads may query one tree at once.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <stdexcept>
#include <vector>

#include "adb/core/detail/sibling_pair_allocator.h"
#include "adb/core/errors.h"
#include "adb/core/geometry.h"
#include "adb/core/mesh.h"

namespace adb {

/// How pc (possible collision cells per node) is counted (paper §3.4).
enum class CellCounting {
  Approximate,  ///< Fig. 5: propagate areas up the tree. O(m log m). The default.
  Exact,        ///< clip every triangle of a node into the node's grid. O(n log n), slower.
};

struct BuildSettings {
  /// Cells per axis of each node's grid: G^3 cells (the paper found 8^3 = 512 best). 1..32.
  int gridResolution = 8;
  /// Triangles per leaf at most, 1..15 (packed in 4 bits of the node).
  int maxLeafTriangles = 4;
  CellCounting counting = CellCounting::Approximate;
  /// [open] A cell is a possible collision cell when its clipped area reaches this fraction
  /// of MaxArea(cell) (the largest polygon fitting in the cell; paper: fraction 1). A smooth
  /// surface crossing a cube cell covers at most MaxArea, so with the paper's value almost no
  /// cell of a smooth mesh counts and every pair gets probability 0; docs/probability-model.md
  /// shows the measurements behind the default. In (0, 1].
  double areaThreshold = 0.35;
};

/// One tree node: 32 bytes, the hot data of the traversal, two per cache line.
struct Node {
  float lo[3];            // 12 bytes: box min, local coordinates, rounded outward
  float hi[3];            // 12 bytes: box max, rounded outward
  float pc;               //  4 bytes: possible collision cells (fractional when approximate)
  std::uint32_t packed;   //  4 bytes: bits 4..31 first child (inner; the second child is
                          //           first + 1) or first triangle (leaf); bits 0..3 the
                          //           leaf's triangle count (0 marks an inner node)

  bool isLeaf() const { return (packed & 0xFu) != 0; }
  std::uint32_t firstChild() const { return packed >> 4; }
  std::uint32_t firstTriangle() const { return packed >> 4; }
  std::uint32_t triangleCount() const { return packed & 0xFu; }
  Vec3 boxLo() const { return Vec3(lo[0], lo[1], lo[2]); }
  Vec3 boxHi() const { return Vec3(hi[0], hi[1], hi[2]); }
};
static_assert(sizeof(Node) == 32, "Node is laid out for two per cache line");

/// Per-node surface statistics, kept apart from Node because only contact generation reads
/// them. 32 bytes.
struct NodeSurface {
  float area;          // total triangle area below the node
  float normal[3];     // area-weighted mean unit normal (zero when the normals cancel)
  float centroid[3];   // area-weighted centroid, local coordinates
  float coherence;     // |sum a_i n_i| / sum a_i in [0, 1]: 1 for a flat patch
};
static_assert(sizeof(NodeSurface) == 32, "NodeSurface layout");

/// How a node's polygons are distributed, read by the traversal next to Node: 32 bytes.
/// The slab {x : |normal . x - offset| <= halfWidth} holds every vertex below the node, so
/// box-and-slab is a tighter bounding volume than the box alone (a curved sheet's nodes are
/// thin along their mean normal). The grid of a node holds about G^3 near-cubic cells (see
/// docs/probability-model.md).
struct NodeDistribution {
  float normal[3];  // 12 bytes: unit slab normal (the mean surface normal, or the box's
                    //           thinnest axis where normals cancel)
  float offset;     //  4 bytes: normal . (a point of the slab's mid-plane)
  float halfWidth;  //  4 bytes: half the slab's width, rounded up
  float side;       //  4 bytes: nominal side h of the node's cells, local units
  float density;    //  4 bytes: possible collision cells / cells of the node's grid, [0, 1]
  float invSide;    //  4 bytes: 1 / side, so that the traversal does not divide
};
static_assert(sizeof(NodeDistribution) == 32, "NodeDistribution layout");

/// Which of 64 cells of a node's box the triangles below it touch: a bounding volume made of
/// cells, read by the traversal after the box and slab tests pass (the pair is apart when the
/// part of either node's box the other can reach holds no touched cell). 24 bytes.
struct NodeOccupancy {
  std::uint64_t cells;     //  8 bytes: bit set where some triangle below the node may reach
                           //           the cell; x + (y << shift[0]) + (z << (shift[0] +
                           //           shift[1])) indexes cell (x, y, z)
  float scale[3];          // 12 bytes: slices per local unit along each axis (0: flat axis)
  std::uint8_t shift[3];   //  3 bytes: 2^shift[k] slices along axis k; the shifts sum to 6
  std::uint8_t triangles : 7;  // triangles below the node, 127 for 127 or more
  std::uint8_t slivers : 1;    // its triangles are slivers: sum of areas below
                               // kSliverFatness x sum of squared longest edges
};
static_assert(sizeof(NodeOccupancy) == 24, "NodeOccupancy layout");

/// Triangles whose area is below this fraction of their longest edge squared are slivers
/// (summed over a node: 0.43 for equilateral triangles, 0.005 for 100:1 ones; 0.02 is about
/// 25:1). The probability model reads a node's surface as small polygons filling its cells;
/// a node of slivers is never accepted on probability (QuerySettings::minTrianglesToAccept).
inline constexpr double kSliverFatness = 0.02;

/// Node records laid out so that siblings share a cache line (SiblingPairAllocator).
template <class T>
using NodeArray = std::vector<T, detail::SiblingPairAllocator<T>>;

class AdbTree {
 public:
  /// Builds the hierarchy and its cell statistics. Throws SettingsError on bad settings and
  /// MeshError for a mesh more than 1e12 or less than 1e-12 units across (boxes and areas
  /// are stored in float) or with a vertex more than 1e150 from the origin.
  explicit AdbTree(const TriangleMesh& mesh, const BuildSettings& settings = {});

  const NodeArray<Node>& nodes() const { return m_nodes; }
  const std::vector<NodeSurface>& surfaces() const { return m_surfaces; }
  const NodeArray<NodeDistribution>& distributions() const { return m_distributions; }
  /// Per node, which of 64 cells of its box its triangles touch.
  const std::vector<NodeOccupancy>& occupancy() const { return m_occupancy; }
  const Node& root() const { return m_nodes[0]; }

  /// Vertices in local coordinates: mesh coordinates minus origin().
  const std::vector<Vec3>& localVertices() const { return m_vertices; }
  /// Triangles in tree order (a leaf owns a contiguous range).
  const std::vector<Triangle>& triangles() const { return m_triangles; }
  /// The mesh's index of the triangle at tree position i.
  std::uint32_t meshTriangle(std::uint32_t i) const { return m_meshTriangle[i]; }
  /// Mesh coordinates of the local origin (the centre of the mesh's bounding box).
  const Vec3& origin() const { return m_origin; }

  const BuildSettings& settings() const { return m_settings; }
  int maxDepth() const { return m_maxDepth; }
  std::size_t triangleCount() const { return m_triangles.size(); }
  /// Bytes held by the tree's arrays (nodes, surfaces, occupancy, triangles, vertices).
  std::size_t memoryBytes() const;
  /// Wall-clock seconds spent building the hierarchy and counting cells.
  double hierarchySeconds() const { return m_hierarchySeconds; }
  double countingSeconds() const { return m_countingSeconds; }

 private:
  friend struct TreeBuilderAccess;
  BuildSettings m_settings;
  NodeArray<Node> m_nodes;
  std::vector<NodeSurface> m_surfaces;
  NodeArray<NodeDistribution> m_distributions;
  std::vector<NodeOccupancy> m_occupancy;
  std::vector<Vec3> m_vertices;
  std::vector<Triangle> m_triangles;
  std::vector<std::uint32_t> m_meshTriangle;
  Vec3 m_origin = Vec3::Zero();
  int m_maxDepth = 0;
  double m_hierarchySeconds = 0.0;
  double m_countingSeconds = 0.0;
};

}  // namespace adb

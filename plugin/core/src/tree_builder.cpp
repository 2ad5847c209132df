// The AABB hierarchy of an AdbTree and its per-node surface statistics.
//
// Split rule: binned SAH with a balance constraint. Each node's triangles are binned by
// centroid (16 bins per axis); of the bin boundaries that leave each child at least a tenth of
// the triangles, the one with the least n_L A(L) + n_R A(R) (A: surface area of the child's
// box) is taken. Where no boundary qualifies (centroids piled into one bin, or a node deeper
// than twice a balanced tree's depth), the median centroid on the longest axis, ties broken by
// index so that the tree does not depend on the partition's internal order.
//
// Why not the median alone (the rule until issue 37): it splits at the object median whatever
// the triangles' sizes, so a node mixing a room's walls with its furniture, or a CAD part's
// long slivers with its small faces, keeps a box as large as its largest triangle at every
// level below. Exact mode against FCL on meshes as they come was 0.13x (a robot in a room) and
// 0.63-0.93x (CAD slivers). With this rule, exact mode against FCL on the same poses
// (docs/study.md, run 4: `adb-tradeoff ... --methods adb,exact,fcl`): quadrotor_base 2.25x,
// diff_arm 2.66x, knot 1.92x, gears 3.19x; the robot in the room 0.27x (0.13x with median
// splits, same run otherwise). The balance constraint keeps what the probability model reads from
// depth (LB = (dA + dB) / (dmaxA + dmaxB), paper section 3.6.3: how far a node is from a leaf)
// close to its meaning in a balanced tree, and the depth within a small factor of log2(n).
// The build stays O(n log n).
#include <algorithm>
#include <cassert>
#include <cmath>
#include <numeric>

#include "tree_builder.h"

namespace adb::detail {
namespace {

struct BuildItem {
  std::uint32_t node;
  std::uint32_t begin, end;  // range in the permutation
  int depth;
};

// Float box that contains the double box: rounded outward, so no query can miss a triangle
// because of the conversion.
void storeBox(Node& n, const Aabb& box) {
  // AdbTree's validation bounds coordinates (1e150) and extents (1e12), so local boxes are
  // finite and far inside float's range: no inf or NaN can reach a stored box.
  assert(box.lo.allFinite() && box.hi.allFinite());
  for (int k = 0; k < 3; ++k) {
    float lo = static_cast<float>(box.lo[k]);
    float hi = static_cast<float>(box.hi[k]);
    if (static_cast<double>(lo) > box.lo[k]) lo = std::nextafter(lo, -INFINITY);
    if (static_cast<double>(hi) < box.hi[k]) hi = std::nextafter(hi, INFINITY);
    n.lo[k] = lo;
    n.hi[k] = hi;
  }
}

constexpr int kBins = 16;
// Each child of a SAH split holds at least this fraction of its parent's triangles.
constexpr double kMinChildFraction = 0.1;

// The bin of centroid coordinate c along `axis` (the axis has a positive centroid extent).
int binOf(double c, const Aabb& cbox, int axis) {
  const double ext = cbox.hi[axis] - cbox.lo[axis];
  const int b = static_cast<int>((c - cbox.lo[axis]) / ext * kBins);
  return std::clamp(b, 0, kBins - 1);
}

// Half the surface area of a box: what the chance that another box meets it grows with.
double halfArea(const Aabb& b) {
  const Vec3 e = b.extent();
  return e.x() * e.y() + e.y() * e.z() + e.z() * e.x();
}

// A SAH split: triangles whose centroid falls in bins below `bin` along `axis` go left.
struct SahSplit {
  int axis = -1, bin = 0;  // axis -1: no boundary qualifies
};

// The best qualifying bin boundary of a node's triangles perm[begin, end) with centroid bounds
// cbox (see the file comment).
SahSplit bestBalancedSplit(const std::vector<std::uint32_t>& perm, std::uint32_t begin,
                           std::uint32_t end, const std::vector<Aabb>& triBox,
                           const std::vector<Vec3>& centroid, const Aabb& cbox) {
  const std::uint32_t count = end - begin;
  SahSplit best;
  double bestCost = INFINITY;
  for (int axis = 0; axis < 3; ++axis) {
    if (!(cbox.hi[axis] - cbox.lo[axis] > 0.0)) continue;
    std::uint32_t n[kBins] = {};
    Aabb box[kBins];
    for (std::uint32_t i = begin; i < end; ++i) {
      const int b = binOf(centroid[perm[i]][axis], cbox, axis);
      ++n[b];
      box[b].grow(triBox[perm[i]]);
    }
    Aabb left[kBins];
    std::uint32_t nl[kBins] = {};
    Aabb acc;
    std::uint32_t c = 0;
    for (int b = 0; b < kBins; ++b) {
      acc.grow(box[b]);
      c += n[b];
      left[b] = acc;
      nl[b] = c;
    }
    Aabb right;
    for (int b = kBins - 1; b >= 1; --b) {
      right.grow(box[b]);
      const std::uint32_t l = nl[b - 1], r = count - l;
      if (l < kMinChildFraction * count || r < kMinChildFraction * count) continue;
      const double cost = l * halfArea(left[b - 1]) + r * halfArea(right);
      if (cost < bestCost) {
        bestCost = cost;
        best.axis = axis;
        best.bin = b;
      }
    }
  }
  return best;
}

}  // namespace

void buildHierarchy(AdbTree& tree, const TriangleMesh& mesh, int maxLeafTriangles) {
  auto& nodes = TreeBuilderAccess::nodes(tree);
  auto& verts = TreeBuilderAccess::vertices(tree);
  const Vec3 origin = mesh.bounds().center();
  TreeBuilderAccess::origin(tree) = origin;
  verts.resize(mesh.vertices().size());
  for (std::size_t i = 0; i < verts.size(); ++i) verts[i] = mesh.vertices()[i] - origin;

  const auto& tris = mesh.triangles();
  const std::size_t n = tris.size();
  std::vector<Aabb> triBox(n);
  std::vector<Vec3> centroid(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) triBox[i].grow(verts[tris[i][k]]);
    centroid[i] = triBox[i].center();  // box centre: cheaper than the mean, same ordering role
  }
  std::vector<std::uint32_t> perm(n);
  std::iota(perm.begin(), perm.end(), 0u);

  nodes.clear();
  nodes.reserve(2 * (n / static_cast<std::size_t>(maxLeafTriangles) + 1));
  nodes.push_back(Node{});
  std::vector<BuildItem> stack{{0u, 0u, static_cast<std::uint32_t>(n), 0}};
  // Twice a balanced tree's depth: below it, median splits (the depth stays logarithmic).
  const double leaves = std::max(1.0, static_cast<double>(n) / maxLeafTriangles);
  const int maxSahDepth = 2 * static_cast<int>(std::ceil(std::log2(leaves))) + 2;
  int maxDepth = 0;
  while (!stack.empty()) {
    const BuildItem item = stack.back();
    stack.pop_back();
    Aabb box, cbox;
    for (std::uint32_t i = item.begin; i < item.end; ++i) {
      box.grow(triBox[perm[i]]);
      cbox.grow(centroid[perm[i]]);
    }
    storeBox(nodes[item.node], box);
    nodes[item.node].pc = 0.0f;
    const std::uint32_t count = item.end - item.begin;
    maxDepth = std::max(maxDepth, item.depth);
    if (count <= static_cast<std::uint32_t>(maxLeafTriangles)) {
      nodes[item.node].packed = (item.begin << 4) | count;
      continue;
    }
    std::uint32_t mid = item.begin + count / 2;
    const SahSplit sah = item.depth < maxSahDepth
                             ? bestBalancedSplit(perm, item.begin, item.end, triBox, centroid, cbox)
                             : SahSplit{};
    if (sah.axis >= 0) {
      const auto at =
          std::partition(perm.begin() + item.begin, perm.begin() + item.end, [&](std::uint32_t t) {
            return binOf(centroid[t][sah.axis], cbox, sah.axis) < sah.bin;
          });
      mid = static_cast<std::uint32_t>(at - perm.begin());
    } else {
      int axis = 0;
      const Vec3 ext = cbox.extent();
      if (ext.y() > ext[axis]) axis = 1;
      if (ext.z() > ext[axis]) axis = 2;
      std::nth_element(perm.begin() + item.begin, perm.begin() + mid, perm.begin() + item.end,
                       [&](std::uint32_t a, std::uint32_t b) {
                         const double ca = centroid[a][axis], cb = centroid[b][axis];
                         return ca < cb || (ca == cb && a < b);
                       });
    }
    const auto first = static_cast<std::uint32_t>(nodes.size());
    nodes.push_back(Node{});
    nodes.push_back(Node{});
    nodes[item.node].packed = first << 4;
    stack.push_back({first + 1, mid, item.end, item.depth + 1});
    stack.push_back({first, item.begin, mid, item.depth + 1});
  }
  TreeBuilderAccess::maxDepth(tree) = maxDepth;

  auto& outTris = TreeBuilderAccess::triangles(tree);
  auto& meshTri = TreeBuilderAccess::meshTriangle(tree);
  outTris.resize(n);
  meshTri.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    outTris[i] = tris[perm[i]];
    meshTri[i] = perm[i];
  }
}

void computeSurfaces(AdbTree& tree) {
  const auto& nodes = tree.nodes();
  auto& surf = TreeBuilderAccess::surfaces(tree);
  surf.assign(nodes.size(), NodeSurface{});
  const auto& verts = tree.localVertices();
  const auto& tris = tree.triangles();
  std::vector<Vec3> areaNormal(nodes.size(), Vec3::Zero());  // sum a_i n_i
  std::vector<Vec3> areaCentroid(nodes.size(), Vec3::Zero());
  std::vector<double> area(nodes.size(), 0.0);
  // Children always have larger indices than their parent: a reverse sweep is bottom-up.
  for (std::size_t i = nodes.size(); i-- > 0;) {
    const Node& node = nodes[i];
    if (node.isLeaf()) {
      for (std::uint32_t t = node.firstTriangle(); t < node.firstTriangle() + node.triangleCount();
           ++t) {
        const Vec3 &a = verts[tris[t][0]], &b = verts[tris[t][1]], &c = verts[tris[t][2]];
        const Vec3 cross = (b - a).cross(c - a);  // |cross| = 2 area; direction = normal
        const double triArea = 0.5 * cross.norm();
        areaNormal[i] += 0.5 * cross;
        areaCentroid[i] += triArea * (a + b + c) / 3.0;
        area[i] += triArea;
      }
    } else {
      for (std::uint32_t c = node.firstChild(); c < node.firstChild() + 2; ++c) {
        areaNormal[i] += areaNormal[c];
        areaCentroid[i] += areaCentroid[c];
        area[i] += area[c];
      }
    }
    NodeSurface& s = surf[i];
    s.area = static_cast<float>(area[i]);
    const double len = areaNormal[i].norm();
    const Vec3 normal = len > 0.0 ? Vec3(areaNormal[i] / len) : Vec3::Zero();
    // Degenerate-only nodes have no area: use the box centre as their centroid.
    const Vec3 centroid = area[i] > 0.0 ? Vec3(areaCentroid[i] / area[i])
                                        : Vec3(0.5 * (node.boxLo() + node.boxHi()));
    for (int k = 0; k < 3; ++k) {
      s.normal[k] = static_cast<float>(normal[k]);
      s.centroid[k] = static_cast<float>(centroid[k]);
    }
    s.coherence = area[i] > 0.0 ? static_cast<float>(std::min(1.0, len / area[i])) : 0.0f;
  }
}

namespace {

// The slab normal of a node: its mean surface normal where the normals agree enough to make a
// thin slab, else the box's thinnest axis (a closed or strongly curved patch).
Vec3 slabNormal(const Node& node, const NodeSurface& surface) {
  // Below this coherence (|sum a n| / sum a) the mean normal is mostly cancellation.
  constexpr float kMinCoherence = 0.3f;
  if (surface.coherence >= kMinCoherence) {
    return Vec3(surface.normal[0], surface.normal[1], surface.normal[2]);
  }
  const Vec3 e = node.boxHi() - node.boxLo();
  int axis = 0;
  if (e.y() < e[axis]) axis = 1;
  if (e.z() < e[axis]) axis = 2;
  return Vec3::Unit(axis);
}

// Rounds a float up so that it is >= x (x >= 0).
float roundUp(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) < x) f = std::nextafter(f, INFINITY);
  return f;
}

}  // namespace

void computeSlabs(AdbTree& tree) {
  const auto& nodes = tree.nodes();
  auto& dist = TreeBuilderAccess::distributions(tree);
  dist.resize(nodes.size());
  const auto ranges = triangleRanges(tree);
  const auto& verts = tree.localVertices();
  const auto& tris = tree.triangles();
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const NodeSurface& surface = tree.surfaces()[i];
    const Vec3 n = slabNormal(nodes[i], surface);
    // The stored (float) normal and offset are what the traversal reads: measure the width
    // against those, in double, and round it up, so the slab is conservative as stored.
    float normal[3];
    for (int k = 0; k < 3; ++k) normal[k] = static_cast<float>(n[k]);
    const Vec3 nf(normal[0], normal[1], normal[2]);
    const Vec3 c(surface.centroid[0], surface.centroid[1], surface.centroid[2]);
    const float offset = static_cast<float>(nf.dot(c));
    double width = 0.0;
    for (std::uint32_t t = ranges[i].first; t < ranges[i].second; ++t) {
      for (std::uint32_t v : tris[t]) width = std::max(width, std::abs(nf.dot(verts[v]) - offset));
    }
    NodeDistribution& d = dist[i];
    for (int k = 0; k < 3; ++k) d.normal[k] = normal[k];
    d.offset = offset;
    d.halfWidth = roundUp(width);
  }
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> triangleRanges(const AdbTree& tree) {
  const auto& nodes = tree.nodes();
  std::vector<std::pair<std::uint32_t, std::uint32_t>> range(nodes.size());
  for (std::size_t i = nodes.size(); i-- > 0;) {
    const Node& node = nodes[i];
    if (node.isLeaf()) {
      range[i] = {node.firstTriangle(), node.firstTriangle() + node.triangleCount()};
    } else {
      range[i] = {range[node.firstChild()].first, range[node.firstChild() + 1].second};
    }
  }
  return range;
}

}  // namespace adb::detail

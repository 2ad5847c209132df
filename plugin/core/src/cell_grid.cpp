// Cell grid of a tree node and the exact clipped-area accumulation: a triangle is split into
// x-slabs, each piece into y-slabs, each of those into z-slabs, and every final piece's area
// is added to its cell. Polygons live in fixed-size stack buffers; nothing is allocated.
#include "cell_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace adb::detail {
namespace {

// A triangle clipped by the 6 planes of one cell has at most 9 vertices. Rounding can, in
// near-degenerate cases, make a piece very slightly non-convex so that a plane crosses it
// more than twice; the slack keeps such pieces intact, and push() never writes past the end.
constexpr int kMaxPolygonVertices = 16;

// Grid coordinates beyond this magnitude (a triangle far outside its box, or cells far below
// the scale of the coordinates) would overflow the products of the area computation; such a
// triangle is not clipped, its area goes whole to the cell of its centroid.
constexpr double kMaxGridCoordinate = 1e100;

// A convex polygon in grid coordinates (cell units: the planes of the grid are the integers).
// The vertex array is left uninitialised on purpose: only the first n vertices are ever read.
struct Polygon {
  int n = 0;
  double v[kMaxPolygonVertices][3];

  void push(const double* p) {
    if (n == kMaxPolygonVertices) return;
    v[n][0] = p[0];
    v[n][1] = p[1];
    v[n][2] = p[2];
    ++n;
  }
};

// a + t (b - a) for t in [0, 1], clamped to the segment so that a rounded intersection can
// never leave the range of its edge (which keeps later slab ranges and crossings sane).
double lerpClamped(double a, double b, double t) {
  const double x = a + t * (b - a);
  return std::clamp(x, std::min(a, b), std::max(a, b));
}

// Splits `in` by the plane x[axis] == plane into the parts below and above it. Vertices on
// the plane go to both; each crossing edge contributes one shared intersection point, whose
// axis coordinate is set to exactly `plane`.
void split(const Polygon& in, int axis, double plane, Polygon& below, Polygon& above) {
  below.n = 0;
  above.n = 0;
  for (int i = 0; i < in.n; ++i) {
    const double* p = in.v[i];
    const double* q = in.v[i + 1 == in.n ? 0 : i + 1];
    const double dp = p[axis] - plane;
    const double dq = q[axis] - plane;
    if (dp <= 0) below.push(p);
    if (dp >= 0) above.push(p);
    if ((dp < 0 && dq > 0) || (dp > 0 && dq < 0)) {
      // Interpolate from the lower end so the point does not depend on the edge direction.
      const double* l = dp < 0 ? p : q;
      const double* h = dp < 0 ? q : p;
      // h[axis] > plane > l[axis] strictly, so the denominator is > 0 (and finite, since grid
      // coordinates are bounded by kMaxGridCoordinate).
      const double t = (plane - l[axis]) / (h[axis] - l[axis]);
      double x[3];
      for (int k = 0; k < 3; ++k) x[k] = lerpClamped(l[k], h[k], t);
      x[axis] = plane;
      below.push(x);
      above.push(x);
    }
  }
}

// Slab holding grid coordinate u: floor(u) clamped to [0, g-1] (NaN -> 0).
int slabOf(double u, int g) {
  if (!(u > 0)) return 0;
  if (u >= g - 1) return g - 1;
  return static_cast<int>(u);
}

// Last slab whose open interior a range ending at u > lowest reaches: ceil(u) - 1, clamped to
// [lowest, g-1]. A range ending exactly on a plane does not enter the slab above it.
int lastSlabOf(double u, int lowest, int g) {
  if (!(u > 1)) return lowest;
  if (u >= g) return g - 1;
  return std::max(lowest, static_cast<int>(std::ceil(u)) - 1);
}

// Cuts `in` into the slabs of `axis` that its coordinate range touches and calls
// emit(piece, slab) for each piece with at least 3 vertices. Below the second plane
// everything goes to the first slab and above the last plane to the last one, which both
// clamps outside parts into the border slabs and makes the pieces partition the polygon.
template <class Emit>
void cutIntoSlabs(const Polygon& in, int axis, int g, Emit&& emit) {
  double mn = in.v[0][axis];
  double mx = mn;
  for (int i = 1; i < in.n; ++i) {
    mn = std::min(mn, in.v[i][axis]);
    mx = std::max(mx, in.v[i][axis]);
  }
  const int first = slabOf(mn, g);
  // Zero extent along the axis (a polygon in a grid plane): one slab, floor(coord).
  const int last = mx > mn ? lastSlabOf(mx, first, g) : first;
  if (first == last) {
    emit(in, first);
    return;
  }
  Polygon below, bufferA, bufferB;
  const Polygon* rest = &in;
  Polygon* next = &bufferA;
  Polygon* spare = &bufferB;
  for (int k = first + 1; k <= last; ++k) {
    split(*rest, axis, static_cast<double>(k), below, *next);
    if (below.n >= 3) emit(below, k - 1);
    rest = next;
    std::swap(next, spare);
    if (rest->n < 3) return;
  }
  emit(*rest, last);
}

}  // namespace

CellGrid CellGrid::over(const Aabb& box, int resolution, double minRelativeThickness) {
  const int g = std::clamp(resolution, kMinGridResolution, kMaxGridResolution);
  const int cells[3] = {g, g, g};
  return over(box, cells, minRelativeThickness);
}

CellGrid CellGrid::over(const Aabb& box, const int (&cellsPerAxis)[3],
                        double minRelativeThickness) {
  int g[3];
  for (int k = 0; k < 3; ++k) g[k] = std::clamp(cellsPerAxis[k], 1, kMaxCellsPerAxis);
  const bool usable = !box.empty() && box.lo.allFinite() && box.hi.allFinite() &&
                      box.extent().allFinite();
  const Vec3 lo = usable ? box.lo : Vec3::Zero();
  Vec3 extent = usable ? box.extent() : Vec3::Zero();
  // Written so that NaN falls to 0.
  const double relative = minRelativeThickness > 0 ? std::min(minRelativeThickness, 1.0) : 0.0;
  const double largestCoordinate =
      std::max(lo.cwiseAbs().maxCoeff(), (lo + extent).cwiseAbs().maxCoeff());
  // Far from the origin a floor of 1e-30 would give grid planes that round to the same double;
  // a few hundred ulps of the coordinates keeps them apart.
  const double floorExtent = std::max(
      {relative * extent.maxCoeff(), kMinGridExtent,
       kMinExtentUlps * std::numeric_limits<double>::epsilon() * largestCoordinate});
  extent = extent.cwiseMax(floorExtent);
  const Vec3 size(extent.x() / g[0], extent.y() / g[1], extent.z() / g[2]);
  return CellGrid{lo, size, {g[0], g[1], g[2]}};
}

void accumulateClippedArea(const CellGrid& grid, const Vec3& a, const Vec3& b, const Vec3& c,
                           double* cellArea) {
  // The true area, from model coordinates exactly as a caller would compute it.
  const double area = 0.5 * (b - a).cross(c - a).norm();
  if (!(area > 0) || !std::isfinite(area)) return;  // degenerate, or not representable

  const int* g = grid.cells;
  // Grid coordinates: in cell units the slab planes are the integers, so slab lookup is a
  // floor and every plane comparison is exact. (Division, not a reciprocal, to match the
  // documented floor((coord - lo) / cellSize) bit for bit.)
  Polygon triangle;
  triangle.n = 3;
  const Vec3* corners[3] = {&a, &b, &c};
  bool bounded = true;
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) {
      const double u = ((*corners[i])[k] - grid.lo[k]) / grid.cellSize[k];
      triangle.v[i][k] = u;
      bounded = bounded && std::abs(u) <= kMaxGridCoordinate;  // false for NaN too
    }
  }

  // Pieces are measured by their area projected onto the plane of the dominant normal axis
  // (2D shoelace in grid units), scaled by true area / projected area of the whole triangle.
  // The scale is the same for every piece of a planar polygon, so the pieces sum to `area`
  // up to rounding (corrected below), and no piece pays for a 3D cross product.
  double normal[3] = {0, 0, 0};
  if (bounded) {
    const double* p = triangle.v[0];
    const double* q = triangle.v[1];
    const double* r = triangle.v[2];
    for (int k = 0; k < 3; ++k) {
      const int s = (k + 1) % 3;
      const int t = (k + 2) % 3;
      normal[k] = (q[s] - p[s]) * (r[t] - p[t]) - (q[t] - p[t]) * (r[s] - p[s]);
    }
  }
  int dominant = 0;
  for (int k = 1; k < 3; ++k) {
    if (std::abs(normal[k]) > std::abs(normal[dominant])) dominant = k;
  }
  const double projected = std::abs(normal[dominant]);  // twice the projected area
  const double scale = 2.0 * area / projected;  // true area per unit of projected grid area
  if (!(projected > 0) || !std::isfinite(projected) || !std::isfinite(scale)) {
    // Not clippable in grid units (out of range, or degenerate only after rounding into grid
    // units): keep the area, put it whole in the centroid's cell.
    int idx[3];
    for (int k = 0; k < 3; ++k) {
      idx[k] = slabOf((triangle.v[0][k] + triangle.v[1][k] + triangle.v[2][k]) / 3.0, g[k]);
    }
    cellArea[grid.cellIndex(idx[0], idx[1], idx[2])] += area;
    return;
  }
  const double sign = normal[dominant] > 0 ? 1.0 : -1.0;
  const int su = (dominant + 1) % 3;
  const int sv = (dominant + 2) % 3;

  // Rounding in the grid coordinates and intersection points costs about eps * (edge length)^2
  // of area in absolute terms, which is a large relative error for a sliver. The pieces' sum
  // is therefore corrected at the end: the residual goes to the cell of the largest piece.
  double added = 0;
  double largestPiece = -1;
  int largestCell = 0;
  auto addPiece = [&](const Polygon& piece, int ix, int iy, int iz) {
    const int index = grid.cellIndex(ix, iy, iz);
    if (&piece == &triangle) {  // never cut: the exact area, no rounding from the shoelace
      cellArea[index] += area;
      added = area;
      return;
    }
    const double u0 = piece.v[0][su];
    const double v0 = piece.v[0][sv];
    double twice = 0;
    for (int i = 1; i + 1 < piece.n; ++i) {
      twice += (piece.v[i][su] - u0) * (piece.v[i + 1][sv] - v0) -
               (piece.v[i + 1][su] - u0) * (piece.v[i][sv] - v0);
    }
    // A rounding sliver can come out with the wrong orientation; it is worth nothing.
    const double pieceArea = std::max(0.0, 0.5 * sign * twice) * scale;
    if (!std::isfinite(pieceArea)) return;
    cellArea[index] += pieceArea;
    added += pieceArea;
    if (pieceArea > largestPiece) {
      largestPiece = pieceArea;
      largestCell = index;
    }
  };

  cutIntoSlabs(triangle, 0, g[0], [&](const Polygon& xPiece, int ix) {
    cutIntoSlabs(xPiece, 1, g[1], [&](const Polygon& yPiece, int iy) {
      cutIntoSlabs(yPiece, 2, g[2],
                   [&](const Polygon& piece, int iz) { addPiece(piece, ix, iy, iz); });
    });
  });
  // Never below zero: the correction takes at most the largest piece back out.
  if (largestPiece >= 0) cellArea[largestCell] += std::max(area - added, -largestPiece);
}

double maxPolygonArea(const Vec3& cellSize) {
  double p = std::abs(cellSize.x());
  double q = std::abs(cellSize.y());
  double r = std::abs(cellSize.z());
  if (p > q) std::swap(p, q);
  if (q > r) std::swap(q, r);
  if (p > q) std::swap(p, q);
  // The diagonal rectangle through the longest edge; hypot keeps tiny p, q from underflowing.
  return r * std::hypot(p, q);
}

}  // namespace adb::detail

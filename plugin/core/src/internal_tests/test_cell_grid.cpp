// Tests of the node cell grid (cell_grid.h): grid construction and padding, exact clipped
// area per cell (conservation, known answers, triangles on grid planes, degenerate input,
// extreme scales) and MaxArea(cell).
#include "cell_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace adb::detail {
namespace {

double triangleArea(const Vec3& a, const Vec3& b, const Vec3& c) {
  return 0.5 * (b - a).cross(c - a).norm();
}

Aabb makeBox(const Vec3& lo, const Vec3& hi) {
  Aabb box;
  box.lo = lo;
  box.hi = hi;
  return box;
}

struct Accumulated {
  std::vector<double> cells;
  double total = 0;
};

Accumulated accumulate(const CellGrid& grid, const std::vector<Vec3>& tris) {
  Accumulated r;
  r.cells.assign(static_cast<std::size_t>(grid.cellCount()), 0.0);
  for (std::size_t i = 0; i + 2 < tris.size(); i += 3) {
    accumulateClippedArea(grid, tris[i], tris[i + 1], tris[i + 2], r.cells.data());
  }
  for (double v : r.cells) r.total += v;
  return r;
}

// Two triangles covering the axis-aligned square with corner `o` and edges `u`, `v`.
std::vector<Vec3> square(const Vec3& o, const Vec3& u, const Vec3& v) {
  return {o, o + u, o + u + v, o, o + u + v, o + v};
}

void expectAllFiniteNonNegative(const std::vector<double>& cells) {
  for (double v : cells) {
    ASSERT_TRUE(std::isfinite(v));
    ASSERT_GE(v, 0.0);
  }
}

// ---------------------------------------------------------------------------------------
// CellGrid::over

TEST(CellGrid, OverKeepsLoAndDividesExtent) {
  const CellGrid grid = CellGrid::over(makeBox(Vec3(-1, 2, 3), Vec3(1, 6, 4)), 8, 1e-3);
  EXPECT_EQ(grid.cells[0], 8);
  EXPECT_EQ(grid.lo, Vec3(-1, 2, 3));
  EXPECT_EQ(grid.cellSize, Vec3(0.25, 0.5, 0.125));
  EXPECT_EQ(grid.cellCount(), 512);
  EXPECT_EQ(grid.cellIndex(1, 2, 3), (3 * 8 + 2) * 8 + 1);
}

TEST(CellGrid, OverClampsResolution) {
  const Aabb box = makeBox(Vec3(0, 0, 0), Vec3(1, 1, 1));
  EXPECT_EQ(CellGrid::over(box, 0, 0.0).cells[0], 1);
  EXPECT_EQ(CellGrid::over(box, -5, 0.0).cells[0], 1);
  EXPECT_EQ(CellGrid::over(box, 32, 0.0).cells[0], 32);
  EXPECT_EQ(CellGrid::over(box, 33, 0.0).cells[0], 32);
}

TEST(CellGrid, FlatBoxIsPaddedKeepingLo) {
  const CellGrid grid = CellGrid::over(makeBox(Vec3(0, 0, 5), Vec3(2, 4, 5)), 8, 1e-3);
  EXPECT_EQ(grid.lo, Vec3(0, 0, 5));
  EXPECT_DOUBLE_EQ(grid.cellSize.x(), 0.25);
  EXPECT_DOUBLE_EQ(grid.cellSize.y(), 0.5);
  EXPECT_DOUBLE_EQ(grid.cellSize.z(), 4e-3 / 8);
  // A thin but non-zero extent is raised too.
  const CellGrid thin = CellGrid::over(makeBox(Vec3(0, 0, 0), Vec3(1e-9, 4, 2)), 4, 1e-2);
  EXPECT_DOUBLE_EQ(thin.cellSize.x(), 4e-2 / 4);
}

TEST(CellGrid, FlatPointBoxAndOddInputsGivePositiveFiniteCells) {
  const Vec3 points[] = {Vec3(0, 0, 0), Vec3(1e5, -1e5, 3), Vec3(1e-300, 0, 0)};
  for (const Vec3& p : points) {
    for (double rel : {0.0, 1e-3, std::nan("")}) {
      const CellGrid grid = CellGrid::over(makeBox(p, p), 8, rel);
      EXPECT_EQ(grid.lo, p);
      EXPECT_TRUE(grid.cellSize.allFinite());
      EXPECT_GT(grid.cellSize.minCoeff(), 0.0);
      // Far from the origin the grid planes stay distinct doubles.
      EXPECT_GT(p.x() + grid.cellSize.x(), p.x());
    }
  }
  const CellGrid empty = CellGrid::over(Aabb{}, 8, 1e-3);
  EXPECT_TRUE(empty.lo.allFinite());
  EXPECT_TRUE(empty.cellSize.allFinite());
  EXPECT_GT(empty.cellSize.minCoeff(), 0.0);
}

// ---------------------------------------------------------------------------------------
// Area conservation

// Random boxes (anisotropic, anywhere in [-10, 10]^3) and random triangles inside them.
TEST(CellGrid, AreaConservationRandomTriangles) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int g : {1, 2, 8, 13}) {
    std::vector<double> cells(static_cast<std::size_t>(g * g * g));
    for (int trial = 0; trial < 10000; ++trial) {
      const Vec3 lo(20 * unit(rng) - 10, 20 * unit(rng) - 10, 20 * unit(rng) - 10);
      const Vec3 size(0.01 + 10 * unit(rng), 0.01 + 10 * unit(rng), 0.01 + 10 * unit(rng));
      const CellGrid grid = CellGrid::over(makeBox(lo, lo + size), g, 1e-3);
      Vec3 v[3];
      for (Vec3& p : v) p = lo + Vec3(unit(rng), unit(rng), unit(rng)).cwiseProduct(size);
      std::fill(cells.begin(), cells.end(), 0.0);
      accumulateClippedArea(grid, v[0], v[1], v[2], cells.data());
      double total = 0;
      for (double c : cells) {
        ASSERT_TRUE(std::isfinite(c));
        ASSERT_GE(c, 0.0);
        total += c;
      }
      const double area = triangleArea(v[0], v[1], v[2]);
      ASSERT_NEAR(total, area, 1e-9 * area) << "G=" << g << " trial " << trial;
    }
  }
}

// Needles and slivers (third vertex within 1e-7 of the box size of the opposite edge): the
// rounding of the clipping is large relative to such areas; the sum must still be exact.
TEST(CellGrid, AreaConservationSlivers) {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int g : {2, 8, 13, 32}) {
    const Vec3 lo(-1, 3, 0.5);
    const Vec3 size(2, 1, 3);
    const CellGrid grid = CellGrid::over(makeBox(lo, lo + size), g, 1e-3);
    std::vector<double> cells(static_cast<std::size_t>(g * g * g));
    for (int trial = 0; trial < 1000; ++trial) {
      const Vec3 a = lo + Vec3(unit(rng), unit(rng), unit(rng)).cwiseProduct(size);
      const Vec3 b = lo + Vec3(unit(rng), unit(rng), unit(rng)).cwiseProduct(size);
      const Vec3 jitter = Vec3(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5);
      const Vec3 c = a + unit(rng) * (b - a) + 1e-7 * jitter.cwiseProduct(size);
      std::fill(cells.begin(), cells.end(), 0.0);
      accumulateClippedArea(grid, a, b, c, cells.data());
      double total = 0;
      for (double v : cells) {
        ASSERT_GE(v, 0.0);
        total += v;
      }
      const double area = triangleArea(a, b, c);
      ASSERT_NEAR(total, area, 1e-9 * area) << "G=" << g << " trial " << trial;
    }
  }
}

// An independent reference: clip the triangle against each cell's six planes separately
// (Sutherland-Hodgman in model coordinates) and compare every cell, not just the sum.
std::vector<Vec3> clipHalfSpace(const std::vector<Vec3>& poly, int axis, double plane,
                                bool keepBelow) {
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec3& p = poly[i];
    const Vec3& q = poly[(i + 1) % poly.size()];
    const double dp = keepBelow ? plane - p[axis] : p[axis] - plane;
    const double dq = keepBelow ? plane - q[axis] : q[axis] - plane;
    if (dp >= 0) out.push_back(p);
    if ((dp > 0 && dq < 0) || (dp < 0 && dq > 0)) out.push_back(p + dp / (dp - dq) * (q - p));
  }
  return out;
}

double polygonArea(const std::vector<Vec3>& poly) {
  Vec3 sum = Vec3::Zero();
  for (std::size_t i = 1; i + 1 < poly.size(); ++i) {
    sum += (poly[i] - poly[0]).cross(poly[i + 1] - poly[0]);
  }
  return 0.5 * sum.norm();
}

TEST(CellGrid, AreaPerCellMatchesReferenceClipping) {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int g : {2, 4, 5}) {
    const Vec3 lo(0.25, -1.5, 2);
    const Vec3 size(1.5, 2, 0.75);
    const CellGrid grid = CellGrid::over(makeBox(lo, lo + size), g, 1e-3);
    for (int trial = 0; trial < 300; ++trial) {
      std::vector<Vec3> tri(3);
      for (Vec3& p : tri) p = lo + Vec3(unit(rng), unit(rng), unit(rng)).cwiseProduct(size);
      const Accumulated r = accumulate(grid, tri);
      const double area = triangleArea(tri[0], tri[1], tri[2]);
      for (int iz = 0; iz < g; ++iz) {
        for (int iy = 0; iy < g; ++iy) {
          for (int ix = 0; ix < g; ++ix) {
            const int idx[3] = {ix, iy, iz};
            std::vector<Vec3> poly = tri;
            for (int k = 0; k < 3 && !poly.empty(); ++k) {
              poly = clipHalfSpace(poly, k, lo[k] + idx[k] * grid.cellSize[k], false);
              poly = clipHalfSpace(poly, k, lo[k] + (idx[k] + 1) * grid.cellSize[k], true);
            }
            const double expected = poly.size() >= 3 ? polygonArea(poly) : 0.0;
            ASSERT_NEAR(r.cells[static_cast<std::size_t>(grid.cellIndex(ix, iy, iz))], expected,
                        1e-10 * area)
                << "G=" << g << " trial " << trial << " cell " << ix << "," << iy << "," << iz;
          }
        }
      }
    }
  }
}

// Vertex coordinates snapped to grid planes half of the time: edges and whole triangles lie
// in grid planes, vertices sit on grid lines and corners. Area must still be conserved.
TEST(CellGrid, AreaConservationSnappedToGridPlanes) {
  std::mt19937_64 rng(777);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int g : {1, 2, 8, 13}) {
    const Vec3 lo(-0.3, 1.7, 2.9);
    const Vec3 size(1.0, 0.7, 1.3);
    const CellGrid grid = CellGrid::over(makeBox(lo, lo + size), g, 1e-3);
    std::uniform_int_distribution<int> plane(0, g);
    std::vector<double> cells(static_cast<std::size_t>(g * g * g));
    for (int trial = 0; trial < 3000; ++trial) {
      Vec3 v[3];
      for (Vec3& p : v) {
        for (int k = 0; k < 3; ++k) {
          const double f = unit(rng) < 0.5 ? plane(rng) / static_cast<double>(g) : unit(rng);
          p[k] = lo[k] + f * size[k];
        }
      }
      // Sometimes force the triangle into one grid plane.
      if (trial % 4 == 0) {
        const int axis = trial / 4 % 3;
        v[1][axis] = v[2][axis] = v[0][axis];
      }
      std::fill(cells.begin(), cells.end(), 0.0);
      accumulateClippedArea(grid, v[0], v[1], v[2], cells.data());
      double total = 0;
      for (double c : cells) {
        ASSERT_TRUE(std::isfinite(c));
        ASSERT_GE(c, 0.0);
        total += c;
      }
      const double area = triangleArea(v[0], v[1], v[2]);
      ASSERT_NEAR(total, area, 1e-9 * area) << "G=" << g << " trial " << trial;
    }
  }
}

TEST(CellGrid, AreaConservationOutsideBoxClampsIntoBorderCells) {
  const CellGrid grid = CellGrid::over(makeBox(Vec3(0, 0, 0), Vec3(1, 1, 1)), 2, 1e-3);
  // In the plane z = 0.25, reaching far beyond the box in x and y.
  const Vec3 a(-1, -1, 0.25), b(3, -0.5, 0.25), c(0.5, 4, 0.25);
  const Accumulated r = accumulate(grid, {a, b, c});
  EXPECT_NEAR(r.total, triangleArea(a, b, c), 1e-12);
  for (int iz = 0; iz < 2; ++iz) {
    for (int iy = 0; iy < 2; ++iy) {
      for (int ix = 0; ix < 2; ++ix) {
        const double v = r.cells[static_cast<std::size_t>(grid.cellIndex(ix, iy, iz))];
        if (iz == 0) {
          EXPECT_GT(v, 0.0);
        } else {
          EXPECT_EQ(v, 0.0);
        }
      }
    }
  }
}

// ---------------------------------------------------------------------------------------
// Known answers

TEST(CellGrid, KnownAnswerTriangleInsideOneCell) {
  const CellGrid grid = CellGrid::over(makeBox(Vec3(0, 0, 0), Vec3(8, 8, 8)), 8, 1e-3);
  const Vec3 a(3.1, 5.2, 1.3), b(3.9, 5.3, 1.8), c(3.4, 5.95, 1.05);
  const Accumulated r = accumulate(grid, {a, b, c});
  const std::size_t cell = static_cast<std::size_t>(grid.cellIndex(3, 5, 1));
  EXPECT_EQ(r.cells[cell], triangleArea(a, b, c));  // untouched by clipping: exact
  for (std::size_t i = 0; i < r.cells.size(); ++i) {
    if (i != cell) {
      EXPECT_EQ(r.cells[i], 0.0) << "cell " << i;
    }
  }
}

TEST(CellGrid, BoundaryPlaneBottomFaceGivesEachBottomCellItsShare) {
  for (const Vec3& lo : {Vec3(0, 0, 0), Vec3(-3.3, 2.1, 7.7)}) {
    for (int g : {1, 2, 8, 13}) {
      const CellGrid grid = CellGrid::over(makeBox(lo, lo + Vec3(1, 1, 1)), g, 1e-3);
      const Accumulated r = accumulate(grid, square(lo, Vec3(1, 0, 0), Vec3(0, 1, 0)));
      const double share = 1.0 / (g * g);
      for (int iz = 0; iz < g; ++iz) {
        for (int iy = 0; iy < g; ++iy) {
          for (int ix = 0; ix < g; ++ix) {
            const double v = r.cells[static_cast<std::size_t>(grid.cellIndex(ix, iy, iz))];
            if (iz == 0) {
              EXPECT_NEAR(v, share, 1e-13) << "G=" << g << " cell " << ix << "," << iy;
            } else {
              EXPECT_EQ(v, 0.0) << "G=" << g << " layer " << iz;
            }
          }
        }
      }
      EXPECT_NEAR(r.total, 1.0, 1e-12);
    }
  }
}

// A unit square lying exactly in a grid plane (every interior plane, and the box faces, of
// every axis) is counted once, in the single layer floor((coord - lo) / cellSize).
TEST(CellGrid, BoundaryPlaneSquareOnGridPlaneCountsOnce) {
  const Vec3 lo(0.5, -2, 1);
  const Vec3 size(1, 1, 1);
  for (int g : {2, 8, 13}) {
    const CellGrid grid = CellGrid::over(makeBox(lo, lo + size), g, 1e-3);
    for (int axis = 0; axis < 3; ++axis) {
      const int s = (axis + 1) % 3;
      const int t = (axis + 2) % 3;
      for (int k = 0; k <= g; ++k) {
        Vec3 o = lo;
        o[axis] = lo[axis] + k * grid.cellSize[axis];
        const Accumulated r =
            accumulate(grid, square(o, Vec3::Unit(s) * size[s], Vec3::Unit(t) * size[t]));
        EXPECT_NEAR(r.total, 1.0, 1e-12) << "G=" << g << " axis " << axis << " plane " << k;
        const double slab = std::floor((o[axis] - lo[axis]) / grid.cellSize[axis]);
        const int layer = static_cast<int>(std::clamp(slab, 0.0, g - 1.0));
        double inLayer = 0;
        for (int i = 0; i < g; ++i) {
          for (int j = 0; j < g; ++j) {
            int idx[3];
            idx[axis] = layer;
            idx[s] = i;
            idx[t] = j;
            inLayer += r.cells[static_cast<std::size_t>(grid.cellIndex(idx[0], idx[1], idx[2]))];
          }
        }
        EXPECT_EQ(inLayer, r.total) << "G=" << g << " axis " << axis << " plane " << k;
      }
    }
  }
}

// The rectangle x + y = c, 0 <= z <= 1 in the unit cube: cell (ix, iy, iz) receives the length
// of the line x + y = c inside the square [ix h, (ix+1) h] x [iy h, (iy+1) h] times h.
TEST(CellGrid, KnownAnswerDiagonalPlane) {
  for (int g : {3, 4, 8}) {
    for (double c : {0.8, 1.0, 1.3}) {
      const CellGrid grid = CellGrid::over(makeBox(Vec3(0, 0, 0), Vec3(1, 1, 1)), g, 1e-3);
      // Corners of the rectangle where the plane cuts the unit cube.
      const Vec3 p0 = c <= 1 ? Vec3(c, 0, 0) : Vec3(1, c - 1, 0);
      const Vec3 p1 = c <= 1 ? Vec3(0, c, 0) : Vec3(c - 1, 1, 0);
      const Vec3 up(0, 0, 1);
      const Accumulated r = accumulate(grid, {p0, p1, p1 + up, p0, p1 + up, p0 + up});
      const double h = 1.0 / g;
      double expectedTotal = 0;
      for (int iz = 0; iz < g; ++iz) {
        for (int iy = 0; iy < g; ++iy) {
          for (int ix = 0; ix < g; ++ix) {
            const double x0 = std::max(ix * h, c - (iy + 1) * h);
            const double x1 = std::min((ix + 1) * h, c - iy * h);
            const double expected = std::sqrt(2.0) * std::max(0.0, x1 - x0) * h;
            expectedTotal += expected;
            EXPECT_NEAR(r.cells[static_cast<std::size_t>(grid.cellIndex(ix, iy, iz))], expected,
                        1e-13)
                << "G=" << g << " c=" << c << " cell " << ix << "," << iy << "," << iz;
          }
        }
      }
      EXPECT_NEAR(r.total, expectedTotal, 1e-12);
      EXPECT_NEAR(r.total, (p1 - p0).norm(), 1e-12);
    }
  }
}

// ---------------------------------------------------------------------------------------
// MaxArea(cell)

TEST(CellGrid, MaxAreaCube) {
  EXPECT_DOUBLE_EQ(maxPolygonArea(Vec3(1, 1, 1)), std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(maxPolygonArea(Vec3(0.125, 0.125, 0.125)), 0.125 * 0.125 * std::sqrt(2.0));
}

TEST(CellGrid, MaxAreaCuboidAnyOrder) {
  // Sides 1 <= 2 <= 3: 3 * sqrt(1 + 4).
  const double expected = 3 * std::sqrt(5.0);
  EXPECT_DOUBLE_EQ(maxPolygonArea(Vec3(1, 2, 3)), expected);
  EXPECT_DOUBLE_EQ(maxPolygonArea(Vec3(3, 1, 2)), expected);
  EXPECT_DOUBLE_EQ(maxPolygonArea(Vec3(2, 3, 1)), expected);
  EXPECT_DOUBLE_EQ(maxPolygonArea(Vec3(-2, 3, -1)), expected);
  // At least the largest face, at most the largest face times sqrt 2.
  EXPECT_GE(maxPolygonArea(Vec3(1, 2, 3)), 6.0);
  EXPECT_LE(maxPolygonArea(Vec3(1, 2, 3)), 6.0 * std::sqrt(2.0));
}

TEST(CellGrid, MaxAreaFlatCell) {
  EXPECT_DOUBLE_EQ(maxPolygonArea(Vec3(2, 0, 3)), 6.0);
  EXPECT_DOUBLE_EQ(maxPolygonArea(Vec3(0, 0, 3)), 0.0);
  // p^2 + q^2 would underflow to 0 here.
  EXPECT_DOUBLE_EQ(maxPolygonArea(Vec3(1e-170, 1, 1e-170)), 1e-170 * std::sqrt(2.0));
}

// ---------------------------------------------------------------------------------------
// Flat boxes

// A 2 x 4 patch in the plane z = 5 made of a 10 x 10 grid of quads: the padded box keeps the
// patch in layer 0, every cell stays finite and the sum is the patch area.
TEST(CellGrid, FlatBoxPatchLandsInLayerZero) {
  const Vec3 lo(0, 0, 5);
  for (int g : {1, 8, 13}) {
    const CellGrid grid = CellGrid::over(makeBox(lo, Vec3(2, 4, 5)), g, 1e-3);
    std::vector<Vec3> tris;
    for (int i = 0; i < 10; ++i) {
      for (int j = 0; j < 10; ++j) {
        const std::vector<Vec3> q =
            square(lo + Vec3(0.2 * i, 0.4 * j, 0), Vec3(0.2, 0, 0), Vec3(0, 0.4, 0));
        tris.insert(tris.end(), q.begin(), q.end());
      }
    }
    const Accumulated r = accumulate(grid, tris);
    expectAllFiniteNonNegative(r.cells);
    EXPECT_NEAR(r.total, 8.0, 1e-12);
    double layer0 = 0;
    for (int iy = 0; iy < g; ++iy) {
      for (int ix = 0; ix < g; ++ix) {
        layer0 += r.cells[static_cast<std::size_t>(grid.cellIndex(ix, iy, 0))];
      }
    }
    EXPECT_EQ(layer0, r.total) << "G=" << g;
  }
}

// With no relative padding at all the flat box still gets a positive thickness and the patch
// still lands in layer 0.
TEST(CellGrid, FlatBoxWithoutRelativePaddingStillWorks) {
  const Vec3 lo(1e5, -1e5, 1e5);
  const CellGrid grid = CellGrid::over(makeBox(lo, lo + Vec3(1, 1, 0)), 8, 0.0);
  EXPECT_GT(grid.cellSize.z(), 0.0);
  const Accumulated r = accumulate(grid, square(lo, Vec3(1, 0, 0), Vec3(0, 1, 0)));
  expectAllFiniteNonNegative(r.cells);
  EXPECT_NEAR(r.total, 1.0, 1e-9);
  for (int iy = 0; iy < 8; ++iy) {
    for (int ix = 0; ix < 8; ++ix) {
      EXPECT_NEAR(r.cells[static_cast<std::size_t>(grid.cellIndex(ix, iy, 0))], 1.0 / 64, 1e-9);
    }
  }
}

// ---------------------------------------------------------------------------------------
// Degenerate and extreme input

TEST(CellGrid, DegenerateTrianglesAddNothing) {
  const CellGrid grid = CellGrid::over(makeBox(Vec3(0, 0, 0), Vec3(1, 1, 1)), 8, 1e-3);
  const Vec3 p(0.3, 0.4, 0.5);
  const Vec3 corner(0.25, 0.5, 0.625);  // a grid vertex
  const std::vector<Vec3> tris = {
      p, p, p,                                                 // a point
      corner, corner, corner,                                  // a point on a grid vertex
      p, p, Vec3(0.9, 0.1, 0.2),                               // repeated vertex
      Vec3(0, 0, 0), Vec3(0.5, 0.5, 0.5), Vec3(1, 1, 1),       // collinear, across cells
      Vec3(0, 0.25, 0.5), Vec3(1, 0.25, 0.5), Vec3(0.5, 0.25, 0.5),  // on a grid line
      Vec3(-5, 0, 0), Vec3(5, 0, 0), Vec3(0, 0, 0),            // collinear, outside the box
  };
  const Accumulated r = accumulate(grid, tris);
  for (double v : r.cells) EXPECT_EQ(v, 0.0);
  // A point box with a point triangle.
  const CellGrid pointGrid = CellGrid::over(makeBox(p, p), 8, 1e-3);
  const Accumulated rp = accumulate(pointGrid, {p, p, p});
  for (double v : rp.cells) EXPECT_EQ(v, 0.0);
}

// Boxes of size 1e3 and 1e-3, near the origin and 1e5 away from it, with random triangles.
TEST(CellGrid, ScaleHugeTinyAndFarBoxesConserveArea) {
  std::mt19937_64 rng(4242);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (double scale : {1e3, 1e-3}) {
    for (double offset : {0.0, 1e5, -1e5}) {
      for (int g : {2, 8, 13}) {
        const Vec3 lo = Vec3(offset, -0.5 * offset, offset) - 0.5 * scale * Vec3::Ones();
        const Vec3 size = scale * Vec3(1.0, 0.6, 1.7);
        const CellGrid grid = CellGrid::over(makeBox(lo, lo + size), g, 1e-3);
        std::vector<double> cells(static_cast<std::size_t>(g * g * g));
        for (int trial = 0; trial < 300; ++trial) {
          Vec3 v[3];
          for (Vec3& q : v) q = lo + Vec3(unit(rng), unit(rng), unit(rng)).cwiseProduct(size);
          std::fill(cells.begin(), cells.end(), 0.0);
          accumulateClippedArea(grid, v[0], v[1], v[2], cells.data());
          double total = 0;
          for (double c : cells) {
            ASSERT_TRUE(std::isfinite(c));
            total += c;
          }
          const double area = triangleArea(v[0], v[1], v[2]);
          ASSERT_NEAR(total, area, 1e-9 * area)
              << "scale " << scale << " offset " << offset << " G=" << g;
        }
      }
    }
  }
}

// Far outside the precondition, nothing may become NaN or infinite.
TEST(CellGrid, ExtremeInputsStayFinite) {
  const CellGrid grid = CellGrid::over(makeBox(Vec3(0, 0, 0), Vec3(1, 1, 1)), 8, 1e-3);
  const CellGrid pointGrid = CellGrid::over(makeBox(Vec3(1, 1, 1), Vec3(1, 1, 1)), 8, 0.0);
  const double big = std::numeric_limits<double>::max();
  const std::vector<Vec3> tris = {
      Vec3(1e300, 0, 0), Vec3(0, 1e300, 0), Vec3(0, 0, 1e300),
      Vec3(-big, -big, 0), Vec3(big, -big, 0), Vec3(0, big, 0),
      Vec3(1e150, 0, 0), Vec3(0, 1e150, 0), Vec3(0, 0, 1e150),
      Vec3(1e-300, 0, 0), Vec3(0, 1e-300, 0), Vec3(0, 0, 1e-300),
      Vec3(0.1, 0.2, 0.3), Vec3(0.9, 0.2, 0.3), Vec3(0.5, 0.2 + 1e-200, 0.3),
  };
  for (const CellGrid* g : {&grid, &pointGrid}) {
    const Accumulated r = accumulate(*g, tris);
    expectAllFiniteNonNegative(r.cells);
    // A triangle of ordinary size far outside a tiny grid keeps its area (clamped to borders).
    const Vec3 a(3, 0, 0), b(0, 3, 0), c(0, 0, 3);
    const Accumulated far = accumulate(*g, {a, b, c});
    expectAllFiniteNonNegative(far.cells);
    EXPECT_NEAR(far.total, triangleArea(a, b, c), 1e-9 * triangleArea(a, b, c));
  }
}

}  // namespace
}  // namespace adb::detail

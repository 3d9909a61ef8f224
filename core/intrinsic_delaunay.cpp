#include "core/intrinsic_delaunay.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "core/errors.h"

namespace symembed {

namespace {

// Area from side lengths (Heron, in the numerically stable ordering of Kahan).
double TriangleArea(double a, double b, double c) {
  if (a < b) std::swap(a, b);
  if (a < c) std::swap(a, c);
  if (b < c) std::swap(b, c);
  const double p = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
  return p > 0.0 ? 0.25 * std::sqrt(p) : 0.0;
}

// Cotangent of the angle opposite side a in a triangle with sides a, b, c.
double CotOpposite(double a, double b, double c) {
  const double area = TriangleArea(a, b, c);
  const double num = b * b + c * c - a * a;
  if (area <= 0.0) return num >= 0.0 ? 1e12 : -1e12;
  return num / (4.0 * area);
}

// Position of the third corner of a triangle with base from (0, 0) to (base, 0), at distance
// r0 from the origin and r1 from (base, 0), above (sign +1) or below (sign -1) the base.
Eigen::Vector2d ThirdCorner(double base, double r0, double r1, double sign) {
  const double x = (r0 * r0 - r1 * r1 + base * base) / (2.0 * base);
  return {x, sign * std::sqrt(std::max(r0 * r0 - x * x, 0.0))};
}

}  // namespace

IntrinsicTriangulation IntrinsicFromSurface(const Surface& s) {
  IntrinsicTriangulation t;
  t.F = s.F;
  t.L.resize(s.NumFaces(), 3);
  for (int f = 0; f < s.NumFaces(); ++f) {
    for (int k = 0; k < 3; ++k) t.L(f, k) = (s.V.row(s.F(f, k)) - s.V.row(s.F(f, (k + 1) % 3))).norm();
  }
  return t;
}

IntrinsicTriangulation IntrinsicDelaunay(const Surface& s, int max_flips) {
  IntrinsicTriangulation t = IntrinsicFromSurface(s);
  const int nf = s.NumFaces();
  if (max_flips <= 0) max_flips = 100 * std::max(nf, 1);
  // Halfedge h = 3 f + k runs from F(f, k) to F(f, k+1); twin[h] runs the other way in the
  // neighbouring face, or -1.
  std::vector<int> twin(3 * nf, -1);
  {
    std::map<std::pair<int, int>, int> directed;
    std::map<std::pair<int, int>, int> count;
    for (int f = 0; f < nf; ++f) {
      for (int k = 0; k < 3; ++k) {
        const int a = t.F(f, k), b = t.F(f, (k + 1) % 3);
        directed[{a, b}] = 3 * f + k;
        ++count[std::minmax(a, b)];
      }
    }
    for (const auto& [ab, h] : directed) {
      if (count[std::minmax(ab.first, ab.second)] != 2) continue;  // boundary or non-manifold
      auto it = directed.find({ab.second, ab.first});
      if (it != directed.end()) twin[h] = it->second;
    }
  }
  auto next = [](int h) { return 3 * (h / 3) + (h % 3 + 1) % 3; };
  auto length = [&](int h) { return t.L(h / 3, h % 3); };
  // Sum of the cotangents of the two angles opposite the edge of h.
  auto cot_sum = [&](int h) {
    const int o = twin[h];
    const int h1 = next(h), h2 = next(h1), o1 = next(o), o2 = next(o1);
    return CotOpposite(length(h), length(h1), length(h2)) +
           CotOpposite(length(o), length(o1), length(o2));
  };
  std::vector<int> stack;
  std::vector<char> queued(3 * nf, 0);
  for (int h = 0; h < 3 * nf; ++h) {
    if (twin[h] > h) {
      stack.push_back(h);
      queued[h] = 1;
    }
  }
  while (!stack.empty() && t.flips < max_flips) {
    const int h = stack.back();
    stack.pop_back();
    queued[h] = 0;
    if (twin[h] < 0 || cot_sum(h) >= -1e-12) continue;
    const int o = twin[h];
    const int f = h / 3, g = o / 3;
    const int hbc = next(h), hca = next(hbc), had = next(o), hdb = next(had);
    const int a = t.F(f, h % 3), b = t.F(g, o % 3);
    const int c = t.F(f, hca % 3), d = t.F(g, hdb % 3);
    if (c == d || f == g) continue;
    const double lab = length(h), lbc = length(hbc), lca = length(hca);
    const double lad = length(had), ldb = length(hdb);
    // Lay out the two triangles on either side of a -> b and measure c - d.
    const Eigen::Vector2d pc = ThirdCorner(lab, lca, lbc, 1.0);
    const Eigen::Vector2d pd = ThirdCorner(lab, lad, ldb, -1.0);
    const double lcd = (pc - pd).norm();
    const int tbc = twin[hbc], tca = twin[hca], tad = twin[had], tdb = twin[hdb];
    // New faces f = (c, a, d) and g = (d, b, c); slot 2 of each is the new edge.
    t.F.row(f) << c, a, d;
    t.L.row(f) << lca, lad, lcd;
    t.F.row(g) << d, b, c;
    t.L.row(g) << ldb, lbc, lcd;
    const int new_h[4] = {3 * f + 0, 3 * f + 1, 3 * g + 0, 3 * g + 1};
    const int old_twin[4] = {tca, tad, tdb, tbc};
    for (int i = 0; i < 4; ++i) {
      twin[new_h[i]] = old_twin[i];
      if (old_twin[i] >= 0) twin[old_twin[i]] = new_h[i];
    }
    twin[3 * f + 2] = 3 * g + 2;
    twin[3 * g + 2] = 3 * f + 2;
    ++t.flips;
    // The four outer edges may have stopped being Delaunay.
    for (int i = 0; i < 4; ++i) {
      const int e = old_twin[i] >= 0 ? std::min(new_h[i], old_twin[i]) : -1;
      if (e >= 0 && !queued[e]) {
        queued[e] = 1;
        stack.push_back(e);
      }
    }
  }
  return t;
}

Eigen::VectorXd IntrinsicFaceAreas(const IntrinsicTriangulation& t) {
  Eigen::VectorXd a(t.F.rows());
  for (int f = 0; f < t.F.rows(); ++f) a(f) = TriangleArea(t.L(f, 0), t.L(f, 1), t.L(f, 2));
  return a;
}

Eigen::SparseMatrix<double> IntrinsicCotanStiffness(const IntrinsicTriangulation& t, int n) {
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(12 * t.F.rows());
  for (int f = 0; f < t.F.rows(); ++f) {
    if (TriangleArea(t.L(f, 0), t.L(f, 1), t.L(f, 2)) <= 0.0) continue;
    for (int k = 0; k < 3; ++k) {
      // Edge k runs from corner k to k+1; its opposite corner is k+2.
      const int i = t.F(f, k), j = t.F(f, (k + 1) % 3);
      const double w = 0.5 * CotOpposite(t.L(f, k), t.L(f, (k + 1) % 3), t.L(f, (k + 2) % 3));
      triplets.emplace_back(i, j, -w);
      triplets.emplace_back(j, i, -w);
      triplets.emplace_back(i, i, w);
      triplets.emplace_back(j, j, w);
    }
  }
  Eigen::SparseMatrix<double> K(n, n);
  K.setFromTriplets(triplets.begin(), triplets.end());
  return K;
}

Eigen::VectorXd IntrinsicVertexAreas(const IntrinsicTriangulation& t, int n) {
  const Eigen::VectorXd area = IntrinsicFaceAreas(t);
  Eigen::VectorXd a = Eigen::VectorXd::Zero(n);
  for (int f = 0; f < t.F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) a(t.F(f, k)) += area(f) / 3.0;
  }
  return a;
}

Eigen::Matrix<double, 3, 2> IntrinsicLayout(const IntrinsicTriangulation& t, int f) {
  Eigen::Matrix<double, 3, 2> p;
  p.row(0).setZero();
  p.row(1) << t.L(f, 0), 0.0;
  p.row(2) = ThirdCorner(t.L(f, 0), t.L(f, 2), t.L(f, 1), 1.0).transpose();
  return p;
}

}  // namespace symembed

// The estimate's fit (logistic_fit.h).
#include "logistic_fit.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace adb::calibrate {
namespace {

double caseWeight(const CaseSamples& c) {
  return 1.0 / static_cast<double>(std::max<std::size_t>(1, c.samples.size()));
}

// The weighted log-loss the fit minimises (each case's samples weigh 1 in all).
double logLoss(const std::vector<CaseSamples>& cases, const Weights& w) {
  double loss = 0.0;
  for (const CaseSamples& c : cases) {
    const double weight = caseWeight(c);
    for (const Sample& s : c.samples) {
      const double p = std::clamp(sigmoidDot(s.f, w), 1e-15, 1.0 - 1e-15);
      loss -= weight * std::log(s.truth ? p : 1.0 - p);
    }
  }
  return loss;
}

Eigen::VectorXd lossGradient(const std::vector<CaseSamples>& cases, const Weights& w) {
  const int kN = static_cast<int>(w.size());
  Eigen::VectorXd gradient = Eigen::VectorXd::Zero(kN);
  for (const CaseSamples& c : cases) {
    const double weight = caseWeight(c);
    for (const Sample& s : c.samples) {
      const Eigen::Map<const Eigen::VectorXd> x(s.f.data(), kN);
      gradient += weight * (sigmoidDot(s.f, w) - (s.truth ? 1.0 : 0.0)) * x;
    }
  }
  return gradient;
}

// Newton's method with step halving (near-separable data make the plain step overshoot) on
// the free weights; the held ones stay at 0.
void newton(const std::vector<CaseSamples>& cases, const std::vector<bool>& free, Weights& w) {
  const int kN = static_cast<int>(w.size());
  for (int iteration = 0; iteration < 50; ++iteration) {
    Eigen::MatrixXd hessian = Eigen::MatrixXd::Identity(kN, kN) * 1e-6;  // a little ridge
    for (const CaseSamples& c : cases) {
      const double weight = caseWeight(c);
      for (const Sample& s : c.samples) {
        const double p = sigmoidDot(s.f, w);
        const Eigen::Map<const Eigen::VectorXd> x(s.f.data(), kN);
        hessian += weight * std::max(p * (1.0 - p), 1e-12) * x * x.transpose();
      }
    }
    Eigen::VectorXd gradient = lossGradient(cases, w);
    for (int i = 0; i < kN; ++i) {
      if (free[i]) continue;
      gradient[i] = 0.0;
      hessian.row(i).setZero();
      hessian.col(i).setZero();
      hessian(i, i) = 1.0;
    }
    const Eigen::VectorXd delta = hessian.ldlt().solve(gradient);
    const double before = logLoss(cases, w);
    double step = 1.0;
    bool improved = false;
    Weights next = w;
    for (int halving = 0; halving < 40 && !improved; ++halving, step *= 0.5) {
      for (int i = 0; i < kN; ++i) next[i] = w[i] - step * delta[i];
      improved = logLoss(cases, next) <= before;
    }
    if (!improved) return;  // no step lowers the loss: converged to rounding
    w = next;
    if (step * delta.norm() < 1e-10) return;
  }
}

}  // namespace

double sigmoidDot(const std::vector<double>& f, const Weights& w) {
  double z = 0.0;
  for (std::size_t i = 0; i < f.size() && i < w.size(); ++i) z += w[i] * f[i];
  if (std::isnan(z)) return 0.5;
  return z >= 0.0 ? 1.0 / (1.0 + std::exp(-z)) : std::exp(z) / (1.0 + std::exp(z));
}

// An active set: fit the free weights; hold the most negative evidence weight at 0; release a
// held weight whose gradient says the loss falls as it grows (the KKT condition); repeat
// until the set is stable. Collinear features (the union, the doubt and the best open bound
// move together) are why one weight at a time.
Weights fitLogistic(const std::vector<CaseSamples>& cases, const std::vector<bool>& nonNegative) {
  const int kN = static_cast<int>(nonNegative.size());
  Weights w(nonNegative.size(), 0.0);
  std::vector<bool> free(nonNegative.size(), true);
  for (int round = 0; round < 4 * kN; ++round) {
    newton(cases, free, w);
    int worst = -1;
    for (int i = 0; i < kN; ++i) {
      if (free[i] && nonNegative[i] && w[i] < 0.0 &&
          (worst < 0 || w[i] < w[worst])) {
        worst = i;
      }
    }
    if (worst >= 0) {
      free[worst] = false;
      w[worst] = 0.0;
      continue;
    }
    const Eigen::VectorXd gradient = lossGradient(cases, w);
    int release = -1;
    for (int i = 0; i < kN; ++i) {
      if (!free[i] && gradient[i] < -1e-9 && (release < 0 || gradient[i] < gradient[release])) {
        release = i;
      }
    }
    if (release < 0) break;  // KKT holds: every held weight wants to stay at 0
    free[release] = true;
  }
  return w;
}

MonotoneMap fitMonotone(const std::vector<CaseSamples>& cases, const Weights& w,
                        int knots) {
  struct Point {
    double p, label, weight;
  };
  std::vector<Point> points;
  for (const CaseSamples& c : cases) {
    const double weight = caseWeight(c);
    for (const Sample& s : c.samples) {
      points.push_back({sigmoidDot(s.f, w), s.truth ? 1.0 : 0.0, weight});
    }
  }
  MonotoneMap map;
  if (points.empty() || knots < 2) return map;
  std::sort(points.begin(), points.end(), [](const Point& l, const Point& r) { return l.p < r.p; });
  // Pool adjacent violators: blocks of (weighted sums of estimate and label, weight, samples).
  struct Block {
    double p, label, weight, count;
  };
  std::vector<Block> blocks;
  for (const Point& q : points) {
    blocks.push_back({q.p * q.weight, q.label * q.weight, q.weight, 1.0});
    while (blocks.size() > 1) {
      const Block& last = blocks.back();
      const Block& prev = blocks[blocks.size() - 2];
      if (prev.label / prev.weight < last.label / last.weight) break;
      const Block merged{prev.p + last.p, prev.label + last.label, prev.weight + last.weight,
                         prev.count + last.count};
      blocks.pop_back();
      blocks.back() = merged;
    }
  }
  // Thinned to about `knots` knots of equal weight, each the mean of the blocks it covers
  // (means of a non-decreasing sequence stay non-decreasing), its frequency smoothed by
  // Laplace's rule over the samples it holds: a block of 200 right answers says 0.995, not 1,
  // so that no budget stop claims the certainty only a finished query has.
  double total = 0.0;
  for (const Block& b : blocks) total += b.weight;
  const double per = total / knots;
  Block group{0.0, 0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    group.p += blocks[i].p;
    group.label += blocks[i].label;
    group.weight += blocks[i].weight;
    group.count += blocks[i].count;
    if (group.weight >= per || i + 1 == blocks.size()) {
      const double frequency = group.label / group.weight;
      map.x.push_back(group.p / group.weight);
      map.y.push_back((frequency * group.count + 1.0) / (group.count + 2.0));
      group = Block{0.0, 0.0, 0.0, 0.0};
    }
  }
  // Smoothing pulls each knot towards 1/2 by its own count: keep the map non-decreasing.
  for (std::size_t i = 1; i < map.y.size(); ++i) map.y[i] = std::max(map.y[i], map.y[i - 1]);
  return map;
}

}  // namespace adb::calibrate

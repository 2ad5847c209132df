// The probability that one unresolved node pair holds a contact: what decides whether a cut
// query's open pair becomes a plausible contact in Bullet (issue 43: "Bullet reads the truth").
//
// An open pair's priority key (OpenPair::p) orders a traversal; it is not a probability: Eq. 3
// is a lower bound, and for a pair the cell model is blind to (few large triangles, slivers)
// the key is its fill discounted by cost. This estimate is fitted (studies/calibrate) on open
// pairs of cut queries over generated models and pairs of models, each labelled by whether a
// triangle below one node really meets a triangle below the other (brute force), so that a
// plausible contact accepted at 0.9 is a contact 9 times in 10.
#pragma once

#include <array>

#include "adb/core/query.h"
#include "adb/core/tree.h"

namespace adb {

inline constexpr int kOpenPairFeatures = 6;
using OpenPairWeights = std::array<double, kOpenPairFeatures>;

/// The features: 1, log(E[X] + 1e-3), the fill (OpenPair::fill, 0 where not worked out),
/// log(the two nodes' triangles, each counted to 127), whether the cell model is blind to the
/// pair (a node under 64 triangles or of slivers), the priority key p; each finite for any
/// input.
std::array<double, kOpenPairFeatures> openPairFeatures(const OpenPair& o, const AdbTree& a,
                                                       const AdbTree& b);

/// sigmoid(w . openPairFeatures(o, a, b)) with the fitted weights, in [0, 1]. `a` and `b` are
/// the trees of the query that left `o` open.
double openPairProbability(const OpenPair& o, const AdbTree& a, const AdbTree& b);

/// The same with given weights (the fit's).
double openPairProbability(const std::array<double, kOpenPairFeatures>& features,
                           const OpenPairWeights& w);

}  // namespace adb

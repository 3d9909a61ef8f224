// Shared steps of the flip scorers: the nearest-neighbour map under each candidate rotation and
// the choice among the four candidates.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "registry/types.h"

namespace symembed {

// For each candidate k of CandidateRotations(): map[k][i] = nearest vertex of the rotated target
// (rows R_k y_t of Yt) to source row i of Ys, dist[k](i) its distance. Ys: #Vs x 3, Yt: #Vt x 3.
struct CandidateMaps {
  std::array<std::vector<int>, 4> map;
  std::array<Eigen::VectorXd, 4> dist;
};
CandidateMaps ComputeCandidateMaps(const Eigen::MatrixX3d& Ys, const Eigen::MatrixX3d& Yt,
                                   int threads = 1);

// Symmetric Chamfer distance between Ys and each rotated target, divided by the mean RMS radius
// of the two sets: mean NN distance source -> target plus target -> source.
std::array<double, 4> ChamferScores(const Eigen::MatrixX3d& Ys, const Eigen::MatrixX3d& Yt,
                                    int threads = 1);

// The candidate indices by increasing score (stable: ties keep index order).
std::array<int, 4> CandidateOrder(const std::array<double, 4>& scores);

// The first `count` of a shape's samples, for a ZoomOut up to k_end coefficients. Throws
// InvalidInputError "<what> has N samples, fewer than k_end" when there are fewer than k_end.
std::vector<int> SamplePrefix(const std::vector<int>& samples, int count, int k_end,
                              const std::string& what);

// The names of CandidateRotations() in order, for messages.
inline constexpr const char* kCandidateNames[4] = {"I", "Rx", "Ry", "Rz"};

// chosen = argmin of scores (first on ties), or `chosen` when it is >= 0 (a stage whose last
// step decides without scores, stages/flip/refined_agreement.h); residual = scores[chosen];
// message lists the scores.
FlipResult MakeFlipResult(const std::array<double, 4>& scores, const std::string& name,
                          int chosen = -1);

// Throws InvalidInputError when a shape's canonical embedding Y does not match its surface.
void CheckFlipPair(const PairInput& pair);

}  // namespace symembed

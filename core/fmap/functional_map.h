// Functional maps between Laplace-Beltrami bases and their conversion to and from
// point-to-point maps.
//
// Convention (pullback, as in [Melzi et al. 2019] ZoomOut: Spectral upsampling for efficient
// shape correspondence, Sec. 4): a point-to-point map T: S -> T, map[i] = T(i), is the matrix
// Pi (#Vs x #Vt) with Pi(i, T(i)) = 1, which pulls a target function g back to the source
// function g o T = Pi g. In reduced bases Phi_s (#Vs x ks) and Phi_t (#Vt x kt) it is the
// ks x kt matrix
//     C = Phi_s^+ Pi Phi_t   (maps target coefficients to source coefficients),
// with Phi_s^+ = Phi_s^T M_s for M_s-orthonormal Phi_s, i.e. the M_s-weighted least-squares
// solution of Phi_s C ~ Pi Phi_t. Conversely, for C close to orthogonal, Pi Phi_t C^T ~ Phi_s
// says that row T(i) of Phi_t C^T is row i of Phi_s, so the point-to-point map of C is
//     T(i) = argmin_j || Phi_t(j, :) C^T - Phi_s(i, :) ||,
// a nearest-neighbour query of the rows of Phi_s among the rows of Phi_t C^T (the paper's
// recovery step). The alternative query of Phi_s C among Phi_t is the same for orthogonal C, but
// the least-squares C shrinks the high frequencies of Phi_s C, and the map drifts as k grows.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace symembed {

// A basis matrix (#V x k) or its first columns (evecs.leftCols(k)) without a copy.
using BasisRef = Eigen::Ref<const Eigen::MatrixXd>;

// Weighted least-squares functional map
//   C = argmin sum_r w(source_ids[r]) || Phi_s(source_ids[r], :) C - Phi_t(target_ids[r], :) ||^2,
// i.e. C = (A^T W A)^{-1} A^T W B. Phi_s: #Vs x ks, Phi_t: #Vt x kt, weights: #Vs (the lumped
// mass for the dense map, ones for a uniform sample). Returns ks x kt. Throws InvalidInputError
// when the ids are out of range or A^T W A is singular (too few points for ks). `gram`, when
// given, is WeightedGram of the same rows and weights, of Phi_s or a basis it is the first
// columns of: its top-left ks x ks block is A^T W A (ZoomOut fits one map per basis size on the
// same points).
Eigen::MatrixXd FitFunctionalMap(const BasisRef& Phi_s, const BasisRef& Phi_t,
                                 const std::vector<int>& source_ids,
                                 const std::vector<int>& target_ids,
                                 const Eigen::VectorXd& weights,
                                 const Eigen::MatrixXd* gram = nullptr);

// FitFunctionalMap from rows already gathered: A (pairs x ks) the source basis at the pairs'
// source points, B (pairs x kt) the target basis at their targets, w (pairs) their weights.
Eigen::MatrixXd FitFunctionalMapFromRows(const BasisRef& A, const BasisRef& B,
                                         const Eigen::VectorXd& w,
                                         const Eigen::MatrixXd* gram = nullptr);

// The rows `ids` of the first `cols` columns of Phi (all by default). Throws InvalidInputError
// for an id out of range.
Eigen::MatrixXd BasisRows(const BasisRef& Phi, const std::vector<int>& ids, int cols = -1);

// A^T W A of FitFunctionalMap for gathered rows A (pairs x ks) and the pairs' weights w.
Eigen::MatrixXd WeightedGram(const BasisRef& A, const Eigen::VectorXd& w);

// The orthogonal C (ks == kt) minimising the same weighted energy: the Procrustes solution
// C = U V^T of A^T W B = U S V^T [Ovsjanikov et al. 2012] Functional maps: a flexible
// representation of maps between shapes.
Eigen::MatrixXd FitOrthogonalFunctionalMap(const BasisRef& Phi_s, const BasisRef& Phi_t,
                                           const std::vector<int>& source_ids,
                                           const std::vector<int>& target_ids,
                                           const Eigen::VectorXd& weights);

// The point-to-point map of C (ks x kt, ks <= Phi_s.cols(), kt <= Phi_t.cols()) for the
// source vertices source_ids: for each, the target vertex whose row of Phi_t(:, :kt) C^T is
// nearest to its row of Phi_s(:, :ks). Target vertices with zero mass_t are never a match.
// sq_dist (optional): squared spectral distances of the matches. target_ids (optional): the
// target vertices that may be matched (empty: all).
std::vector<int> PointMapFromFunctionalMap(const Eigen::MatrixXd& Phi_s,
                                           const Eigen::MatrixXd& Phi_t,
                                           const Eigen::VectorXd& mass_t, const Eigen::MatrixXd& C,
                                           const std::vector<int>& source_ids,
                                           std::vector<double>* sq_dist = nullptr,
                                           const std::vector<int>& target_ids = {});

// The target vertices a point map may land on: target_ids (every vertex when empty) that have
// positive mass_t. Throws InvalidInputError when none has.
std::vector<int> MatchableTargets(const Eigen::VectorXd& mass_t,
                                  const std::vector<int>& target_ids = {});

// PointMapFromFunctionalMap from rows already gathered: for each row of Q (queries x ks, the
// source basis at the query points), the entry of `targets` whose row of P (targets x kt, the
// target basis at those vertices) times C^T is nearest. Side columns (optional, m of them:
// target_side targets x m, query_side queries x m) are appended to both sides, so that a query
// also pays the squared distance between its side row and the target's.
std::vector<int> NearestUnderMap(const BasisRef& Q, const BasisRef& P,
                                 const std::vector<int>& targets, const Eigen::MatrixXd& C,
                                 std::vector<double>* sq_dist = nullptr,
                                 const BasisRef& target_side = Eigen::MatrixXd(),
                                 const BasisRef& query_side = Eigen::MatrixXd());

// ||C^T C - I||_F^2 / k for a k x k functional map: the per-scale term of the ZoomOut energy,
// 0 for an area-preserving (orthogonal) map.
double OrthogonalityDefect(const Eigen::MatrixXd& C);

// Euclidean farthest point sampling of `count` rows of V among those with keep[i] (all when keep is
// empty), started at the first kept vertex. Returns ids in sampling order.
std::vector<int> EuclideanFarthestPoints(const Eigen::MatrixX3d& V, int count,
                                         const std::vector<bool>& keep = {});

// Throws InvalidInputError unless map has num_source entries, each in [0, num_target).
void CheckPointMap(const std::vector<int>& map, int num_source, int num_target);

}  // namespace symembed

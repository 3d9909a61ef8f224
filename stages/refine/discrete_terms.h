// The energy terms of discrete functional-map optimisation, each written as a pair of embeddings
// whose nearest-neighbour query minimises the term over point maps.
//
// [Ren, Melzi, Wonka & Ovsjanikov 2021] Discrete optimization for shape matching: the usual
// functional-map energies (descriptor preservation, Laplacian commutativity, orthogonality,
// bijectivity, and the "proper" constraint that the functional map be the one a point map
// induces) are each rewritten, for a fixed functional map, as a sum over the points of a shape
// X of a squared distance between an embedding of the point and an embedding of its image on
// Y. Their weighted sum is then minimised over point maps exactly, point by point, by one
// nearest-neighbour query in the embeddings stacked side by side, each scaled by the square
// root of its weight.
//
// Convention (core/fmap/functional_map.h): a point map T: X -> Y is the matrix Pi
// (#X x #Y); its functional map C_xy = Phi_x^+ Pi Phi_y (k x k) takes coefficients on Y to
// coefficients on X; C_yx is the functional map of a map Y -> X (the inverse direction, for
// bijectivity). With near-orthogonal maps, Pi Phi_y ~ Phi_x C_xy and C_xy C_yx ~ I, which give
// the point-map forms
//   orthogonality  E = || Pi Phi_y C_xy^T - Phi_x ||^2        (C_xy^T C_xy = I)
//   bijectivity    E = || Pi Phi_y C_yx - Phi_x ||^2          (C_xy C_yx = I)
//   proper         E = || Pi Phi_y - Phi_x C_xy ||^2          (C_xy = Phi_x^+ Pi Phi_y)
//   Laplacian      E = || Pi Phi_y L_y C_xy^T - Phi_x L_x ||^2 (C_xy L_y = L_x C_xy)
//   descriptors    E = || Pi Phi_y A_y - Phi_x A_x ||^2       (C_xy A_y = A_x)
//   embedding      E = || Pi Z_y - Z_x ||^2                   (a point lands near itself)
// with L_x, L_y the diagonal matrices of the first k eigenvalues of each shape (both divided by
// one scale, ScaledEigenvalues) and A_x, A_y descriptor coefficients in the bases (k x q). Each
// norm is summed over the rows of X with a weight per row (the lumped areas, or ones on a
// sample). The rows of X and Y passed to a term are the basis at the query points and at the
// candidate points (any subsets of the shapes' vertices), first k columns. The embedding term
// does not depend on the functional maps: Z_x, Z_y are the points of both shapes in one frame
// where a point and its image lie close (the pipeline's aligned embeddings), which anchors the
// map to where the matching stage put each region while the spectral terms sharpen it.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/fmap/functional_map.h"

namespace symembed {

// A term's embeddings: query row r (of X's query points) and point row c (of Y's candidates);
// the term's energy of a map T is sum_r w(r) || query(r, :) - points(T(r), :) ||^2.
struct TermRows {
  Eigen::MatrixXd query;
  Eigen::MatrixXd points;
};

TermRows OrthogonalityRows(const BasisRef& X, const BasisRef& Y, const Eigen::MatrixXd& C_xy);
TermRows BijectivityRows(const BasisRef& X, const BasisRef& Y, const Eigen::MatrixXd& C_yx);
TermRows ProperRows(const BasisRef& X, const BasisRef& Y, const Eigen::MatrixXd& C_xy);
// lambda_x, lambda_y: the first k eigenvalues of each shape, already scaled.
TermRows LaplacianRows(const BasisRef& X, const BasisRef& Y, const Eigen::VectorXd& lambda_x,
                       const Eigen::VectorXd& lambda_y, const Eigen::MatrixXd& C_xy);
// A_x, A_y: descriptor coefficients, k x q each.
TermRows DescriptorRows(const BasisRef& X, const BasisRef& Y, const Eigen::MatrixXd& A_x,
                        const Eigen::MatrixXd& A_y);

// Z_x, Z_y: the points' coordinates at the query points and at the candidates (d columns each).
TermRows EmbeddingRows(const Eigen::MatrixXd& Z_x, const Eigen::MatrixXd& Z_y);

// The first k eigenvalues of two shapes divided by one scale, the mean of their k-th
// eigenvalues, so that the commutativity term compares the two spectra on one footing and its
// size does not grow with k. Throws InvalidInputError when the k-th eigenvalues are not
// positive or either spectrum has fewer than k values.
void ScaledEigenvalues(const Eigen::VectorXd& evals_x, const Eigen::VectorXd& evals_y, int k,
                       Eigen::VectorXd* lambda_x, Eigen::VectorXd* lambda_y);

// sum_r w(r) || rows.query(r, :) - rows.points(map[r], :) ||^2. map: one entry per query row,
// each a row of rows.points; w: one weight per query row.
double TermEnergy(const TermRows& rows, const std::vector<int>& map, const Eigen::VectorXd& w);

// The terms side by side, each scaled by sqrt(weight); terms of weight 0 are left out. weights
// and terms have one entry per term, weights >= 0 with at least one positive.
TermRows StackTerms(const std::vector<TermRows>& terms, const std::vector<double>& weights);

// Every term above but the embedding's is linear in the basis rows: its rows for queries X and
// candidates Y are X L and Y L' for the rows it gives at identity bases (X = Y = I_k), L and L'
// (k x d). ReduceTerms takes those terms stacked (`maps`: StackTerms of their rows at identity
// bases, query side L_x and point side L_y, k x D) and reduces them to k coordinates: with
// L_y^T = Q R (Q: D x k with orthonormal columns, R: k x k),
//   || X_r L_x - Y_c L_y ||^2 = || X_r L_x Q - Y_c R^T ||^2 + X_r G X_r^T,
//   G = L_x L_x^T - L_x Q Q^T L_x^T  (k x k),
// and the last term does not depend on the candidate c, so the nearest candidate of each query
// row is that of the stacked rows. rows.query: X L_x Q, rows.points: Y R^T, each followed by the
// embedding term's points Z_x, Z_y scaled by sqrt(embedding_weight) when both are given. The
// stacked energy of a map with weights w is the weighted sum of the reduced squared distances
// plus sum_ij G_ij (X^T W X)_ij (up to rounding), so the Gram matrix of the query rows gives it
// without a pass over the rows. D must be at least k (one of orthogonality, bijectivity,
// proper, Laplacian).
struct ReducedTerms {
  TermRows rows;
  Eigen::MatrixXd G;
};
ReducedTerms ReduceTerms(const BasisRef& X, const BasisRef& Y, const TermRows& maps,
                         const Eigen::MatrixXd* Z_x, const Eigen::MatrixXd* Z_y,
                         double embedding_weight);

// The functional forms, per basis size (0 for an exact map): ||C_xy C_yx - I||_F^2 / k and
// ||C_xy L_y - L_x C_xy||_F^2 / k.
double BijectivityDefect(const Eigen::MatrixXd& C_xy, const Eigen::MatrixXd& C_yx);
double CommutativityDefect(const Eigen::MatrixXd& C_xy, const Eigen::VectorXd& lambda_x,
                           const Eigen::VectorXd& lambda_y);

}  // namespace symembed

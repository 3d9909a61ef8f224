// ZoomOut: refinement of a point-to-point map by spectral upsampling.
//
// [Melzi et al. 2019] ZoomOut: Spectral upsampling for efficient shape correspondence. Starting
// from a point-to-point map T: S -> T, alternate (i) the functional map C_k of T in the first k
// Laplace-Beltrami eigenfunctions (least squares, functional_map.h) and (ii) T from C_k by
// nearest neighbours in the k-dimensional spectral embedding, growing k from k_start to k_end by
// step. Given a sample of source vertices, the iterations run on the sample only (the paper's
// fast variant) and only the last nearest-neighbour query maps every source vertex.
//
// ZoomOut is a local method: a region the initial map sends to the wrong part of the target stays
// there once the basis has grown, and where it ends depends on the first basis size. With
// extra_k_starts the iterations also run from each of those sizes, and the run whose map is best
// explained by a functional map at k_end (lowest mean squared spectral distance of its matches,
// the paper's per-point energy at the last size) is kept; only its last query is dense.
#pragma once

#include <Eigen/Core>
#include <string>
#include <type_traits>
#include <vector>

#include "core/range.h"
#include "core/spectral.h"
#include "core/stage_status.h"

namespace symembed {

// Visits k_start, k_end and step, the basis sizes of a schedule grown like ZoomOut's, with the
// ranges Options declares (kKStart, kKEnd, kStep): the start of an options struct's Fields
// (core/range.h).
template <typename Self, typename Visit>
void BasisSizeFields(Self& self, Visit&& visit) {
  using Options = std::remove_const_t<Self>;
  visit("k_start", self.k_start, Options::kKStart);
  visit("k_end", self.k_end, Options::kKEnd);
  visit("step", self.step, Options::kStep);
}

struct ZoomOutOptions {
  int k_start = 20;  // basis size of the first functional map
  static constexpr Range kKStart = Range::Closed(1, 1000);
  int k_end = 120;  // basis size of the last one (>= k_start; both bases need k_end pairs)
  static constexpr Range kKEnd = Range::Closed(1, 1000);
  int step = 5;  // increment of k per iteration; k_end is always the last size
  static constexpr Range kStep = Range::Closed(1, 1000);
  // Further first basis sizes to run from, each in kKStart and <= k_end, distinct and
  // != k_start; empty: one run.
  std::vector<int> extra_k_starts;
  // With samples: true maps every source vertex in the last iteration; false maps only the
  // samples (the other entries of the result keep the initial map).
  bool dense_result = true;

  // The options as the config names them (core/range.h), besides extra_k_starts.
  template <typename Self, typename Visit>
  static void Fields(Self& self, Visit&& visit) {
    BasisSizeFields(self, visit);
  }
  bool IsValid(std::string* error) const;
};

struct ZoomOutResult {
  std::vector<int> map;                   // #Vs: target vertex of each source vertex
  std::vector<int> k;                     // per iteration: basis size
  std::vector<double> orthogonality;      // per iteration: ||C_k^T C_k - I||_F^2 / k
  std::vector<double> spectral_residual;  // per iteration: mean squared NN spectral distance
  int changed = 0;                        // source vertices whose target changed
  int start = 0;                          // first basis size of the kept run
  // With extra_k_starts: each run's residual at k_end on the active points, in the order
  // k_start, extra_k_starts...; empty for a single run.
  std::vector<double> start_residuals;
  StageStatus status;
};

// What ZoomOut computes from the bases, the samples and the options alone: the active points'
// basis rows and their Gram matrix, and the targets they may land on with those targets' rows.
// Built once, it refines several initial maps between the same bases (the flip terms refine two
// to four candidate maps of a pair); Run gives what ZoomOut gives for the same arguments. Keeps
// references to the bases, which must outlive it.
class ZoomOutSetup {
 public:
  // Arguments as for ZoomOut below; throws what it throws for them.
  ZoomOutSetup(const LaplaceBasis& source, const LaplaceBasis& target,
               const std::vector<int>& samples, const ZoomOutOptions& options,
               const std::vector<int>& target_samples = {});

  // ZoomOut from initial_map (#Vs entries in [0, #Vt)).
  ZoomOutResult Run(const std::vector<int>& initial_map) const;

 private:
  // The first k columns of the target basis at the rows `ids`: from target_rows_ for the
  // matchable targets (every id after a first query), from the basis for the others.
  Eigen::MatrixXd TargetRows(const std::vector<int>& ids, int k) const;

  const LaplaceBasis& source_;
  const LaplaceBasis& target_;
  ZoomOutOptions options_;
  bool sampled_;                      // iterations on given samples (else on every vertex)
  int target_sample_count_;           // target samples they map to (0: every target vertex)
  std::vector<int> active_;           // the source vertices the iterations run on
  Eigen::VectorXd active_weights_;    // their least-squares weights
  Eigen::MatrixXd source_rows_;       // their basis rows, k_end columns
  Eigen::MatrixXd gram_;              // A^T W A of source_rows_
  std::vector<int> targets_;          // the target vertices they may land on
  Eigen::MatrixXd target_rows_;       // their basis rows, k_end columns
  std::vector<int> target_row_;       // per target vertex: its row in target_rows_, or -1
};

// source, target: bases with at least k_end eigenpairs (first k_end used). initial_map: #Vs
// entries in [0, #Vt). samples: source vertex ids to iterate on (empty: every vertex, with the
// lumped mass as least-squares weights; else uniform weights, and enough well-spread vertices to
// determine k_end coefficients, in practice a few times k_end). Throws ConfigError for invalid
// options, InvalidInputError for inconsistent inputs. target_samples (optional, with samples):
// the target vertices the sampled iterations map to (empty: all); the dense last query of
// dense_result maps to every target vertex.
ZoomOutResult ZoomOut(const LaplaceBasis& source, const LaplaceBasis& target,
                      const std::vector<int>& initial_map, const std::vector<int>& samples,
                      const ZoomOutOptions& options, const std::vector<int>& target_samples = {});

// The basis sizes of one ZoomOut run from `start`: start, start + step, ... below k_end, then
// k_end.
std::vector<int> ZoomOutBasisSizes(int start, const ZoomOutOptions& options);

// The source vertices ZoomOut iterates on and their least-squares weights: `samples` with unit
// weights, or every vertex with its lumped mass when `samples` is empty. Throws
// InvalidInputError "<who>: sample id out of range".
struct ZoomOutActive {
  std::vector<int> ids;
  Eigen::VectorXd weights;  // per entry of ids
};
ZoomOutActive ZoomOutActivePoints(const char* who, const LaplaceBasis& source,
                                  const std::vector<int>& samples);

// Throws InvalidInputError "<who>: k_end = K but the bases have A and B eigenpairs" unless
// both bases have at least k_end eigenpairs (ZoomOut and the refinements that grow a basis).
void CheckBasesReach(const char* who, const LaplaceBasis& source, const LaplaceBasis& target,
                     int k_end);

}  // namespace symembed

// The flip stages: thin adapters around the scorers (extrinsic, chamfer, hks, oracle).
#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "core/errors.h"
#include "stages/flip/descriptor_map.h"
#include "stages/flip/extrinsic.h"
#include "stages/flip/flip_common.h"
#include "stages/flip/hks.h"
#include "stages/flip/oracle.h"
#include "stages/flip/orientation.h"
#include "stages/flip/refined_agreement.h"
#include "stages/register.h"

namespace symembed {
namespace {

const Eigen::MatrixXd& AuxOf(const ShapeData& shape, const char* key, const char* stage) {
  auto it = shape.aux.find(key);
  if (it == shape.aux.end()) {
    throw InvalidInputError(std::string("flip ") + stage + ": shape '" + shape.name +
                            "' has no '" + key + "' (PrepareShape was not called)");
  }
  return it->second;
}

// The ZoomOut schedule of the orientation and refined terms, from the options <prefix>k_start,
// k_end, step, samples and target_samples.
void ReadZoomOutSchedule(OptionReader& o, const std::string& prefix, FlipZoomOutSchedule* out) {
  out->k_start = o.GetInt(prefix + "k_start", out->k_start, 1, 1000);
  out->k_end = o.GetInt(prefix + "k_end", out->k_end, 1, 1000);
  out->step = o.GetInt(prefix + "step", out->step, 1, 1000);
  out->samples = o.GetInt(prefix + "samples", out->samples, 1, 100000);
  out->target_samples = o.GetInt(prefix + "target_samples", out->target_samples, 0, 100000);
}

// The descriptor term's per-shape products (WksProducts).
constexpr const char* kWksPKey = "extrinsic_wks_P";
constexpr const char* kWksQKey = "extrinsic_wks_Q";

WksProducts WksProductsOf(const ShapeData& shape) {
  return {AuxOf(shape, kWksPKey, "extrinsic"), AuxOf(shape, kWksQKey, "extrinsic")};
}

class ExtrinsicStage : public FlipStage {
 public:
  ExtrinsicStage(ExtrinsicFlipOptions options, double orientation_weight,
                 OrientationOptions orientation, double descriptor_weight,
                 DescriptorMapOptions descriptor, bool refined_on,
                 RefinedAgreementOptions refined)
      : options_(options), orientation_weight_(orientation_weight), orientation_(orientation),
        descriptor_weight_(descriptor_weight), descriptor_(descriptor),
        refined_on_(refined_on), refined_(refined) {}
  void PrepareShape(ShapeData& shape) const override {
    shape.aux[kExtrinsicFeaturesKey] = ExtrinsicFeatures(shape.surface, options_.smoothing_rings);
    LaplaceBasisOptions basis;
    basis.k = BasisSize();
    if (basis.k > 0) EnsureLaplaceBasis(shape.surface, basis, &shape.aux);
    if (descriptor_weight_ > 0.0) {
      // The descriptor term's products over the shape's vertices, once per shape.
      const WksProducts products = ComputeWksProducts(GetLaplaceBasis(shape.aux, basis.k),
                                                      descriptor_.k, descriptor_.eigenpairs);
      shape.aux[kWksPKey] = products.P;
      shape.aux[kWksQKey] = products.Q;
    }
  }
  int PrepareVersion() const override { return 2; }  // 2: the descriptor term's products
  FlipResult Run(const PairInput& pair) const override {
    CheckFlipPair(pair);
    // One set of candidate maps for both terms.
    const CandidateMaps maps = ComputeCandidateMaps(pair.source.Y, pair.target.Y, options_.threads);
    const Eigen::MatrixXd& Fs = AuxOf(pair.source, kExtrinsicFeaturesKey, "extrinsic");
    const Eigen::MatrixXd& Ft = AuxOf(pair.target, kExtrinsicFeaturesKey, "extrinsic");
    ExtrinsicScores s = ExtrinsicFlipScores(pair.source.Y, pair.target.Y, Fs, Ft, options_, maps);
    // One copy of each basis for all spectral terms, into storage the thread keeps from pair to
    // pair.
    thread_local LaplaceBasis source_basis, target_basis;
    if (BasisSize() > 0) {
      GetLaplaceBasis(pair.source.aux, BasisSize(), &source_basis);
      GetLaplaceBasis(pair.target.aux, BasisSize(), &target_basis);
    }
    DescriptorAgreement descriptor;
    if (descriptor_weight_ > 0.0) {
      descriptor = DescriptorMapAgreement(pair.source.Y, pair.target.Y, source_basis,
                                          target_basis, WksProductsOf(pair.source),
                                          WksProductsOf(pair.target), pair.source.samples,
                                          descriptor_);
      for (int k = 0; k < 4; ++k) {
        s.total[k] += descriptor_weight_ * (1.0 - descriptor.agreement[k]) / 2.0;
      }
    }
    OrientationScores orientation;
    if (orientation_weight_ > 0.0) {
      const CandidateOrientation measure(pair.source.surface, pair.target.surface, source_basis,
                                         target_basis, pair.source.samples, pair.target.samples,
                                         orientation_);
      orientation = AddOrientationTerm(s.total, orientation_weight_, maps, measure);
      s.total = orientation.total;
    }
    RefinedChoice refined;
    if (refined_on_) {
      refined = RefinedFrontBackChoice(s.total, pair.source, pair.target, source_basis,
                                       target_basis, Fs, Ft, refined_);
    }
    FlipResult result = MakeFlipResult(s.total, "extrinsic", refined_on_ ? refined.chosen : -1);
    std::ostringstream detail;
    detail << "; local";
    for (double v : s.local) detail << " " << v;
    detail << "; global";
    for (double v : s.global) detail << " " << v;
    if (descriptor_weight_ > 0.0) {
      detail << "; descriptor";
      for (double v : descriptor.agreement) detail << " " << v;
    }
    if (orientation_weight_ > 0.0) {
      // Candidates that could not have the lowest total are not measured ("-").
      detail << "; orientation";
      for (double v : orientation.orientation) {
        if (std::isnan(v)) detail << " -";
        else detail << " " << v;
      }
    }
    if (refined_on_) {
      // Disagreement / orientation of the best candidate and its partner ("-": not refined).
      detail << "; refined";
      for (int k = 0; k < 4; ++k) {
        if (std::isnan(refined.disagreement[k])) detail << " -";
        else detail << " " << refined.disagreement[k] << "/" << refined.orientation[k];
      }
      if (refined.chosen != refined.best) {
        detail << "; refined maps choose " << kCandidateNames[refined.chosen] << " over "
               << kCandidateNames[refined.best] << " (score " << refined.score[refined.chosen]
               << " against " << refined.score[refined.best] << ")";
      }
    }
    result.status.message += detail.str();
    return result;
  }

 private:
  // Eigenpairs the spectral terms need (0: none is on).
  int BasisSize() const {
    return std::max({orientation_weight_ > 0.0 ? orientation_.zoomout.k_end : 0,
                     descriptor_weight_ > 0.0 ? descriptor_.eigenpairs : 0,
                     refined_on_ ? refined_.zoomout.k_end : 0});
  }

  ExtrinsicFlipOptions options_;
  double orientation_weight_;
  OrientationOptions orientation_;
  double descriptor_weight_;
  DescriptorMapOptions descriptor_;
  bool refined_on_;
  RefinedAgreementOptions refined_;
};

class ChamferStage : public FlipStage {
 public:
  explicit ChamferStage(int threads) : threads_(threads) {}
  FlipResult Run(const PairInput& pair) const override {
    CheckFlipPair(pair);
    return MakeFlipResult(ChamferScores(pair.source.Y, pair.target.Y, threads_), "chamfer");
  }

 private:
  int threads_;
};

class HksStage : public FlipStage {
 public:
  explicit HksStage(HksFlipOptions options) : options_(options) {}
  void PrepareShape(ShapeData& shape) const override {
    LaplaceBasisOptions basis;
    basis.k = options_.eigenpairs;
    EnsureLaplaceBasis(shape.surface, basis, &shape.aux);
  }
  FlipResult Run(const PairInput& pair) const override {
    CheckFlipPair(pair);
    const LaplaceBasis source = GetLaplaceBasis(pair.source.aux, options_.eigenpairs);
    const LaplaceBasis target = GetLaplaceBasis(pair.target.aux, options_.eigenpairs);
    return MakeFlipResult(
        HksFlipScores(pair.source.Y, pair.target.Y, source, target, options_), "hks");
  }

 private:
  HksFlipOptions options_;
};

class OracleStage : public FlipStage {
 public:
  explicit OracleStage(int threads) : threads_(threads) {}
  FlipResult Run(const PairInput& pair) const override {
    return MakeFlipResult(OracleFlipScores(pair, threads_), "oracle");
  }

 private:
  int threads_;
};

}  // namespace

void RegisterFlipStages(Registry& registry) {
  registry.Add("flip", "extrinsic",
               "curvature features of the original surfaces, compared locally through each "
               "candidate's NN map and globally (front/back, top/bottom distributions), plus "
               "the orientation of each candidate's map after a short ZoomOut, plus its "
               "agreement with a wave-kernel-signature functional map, plus the curvature "
               "agreement and orientation, after ZoomOut from k = 20, of the maps of the best "
               "candidate and of its front-back partner, which replaces it when clearly better",
               [](OptionReader& o) -> std::unique_ptr<Stage> {
                 ExtrinsicFlipOptions e;
                 e.local_weight = o.GetDouble("local_weight", e.local_weight, 0.0);
                 e.global_weight = o.GetDouble("global_weight", e.global_weight, 0.0);
                 e.chamfer_weight = o.GetDouble("chamfer_weight", e.chamfer_weight, 0.0);
                 e.profile_bins = o.GetInt("profile_bins", e.profile_bins, 1, 1000);
                 e.histogram_bins = o.GetInt("histogram_bins", e.histogram_bins, 1, 1000);
                 e.smoothing_rings = o.GetInt("smoothing_rings", e.smoothing_rings, 0, 100);
                 e.threads = o.GetInt("threads", e.threads, 0, 256);
                 const double orientation_weight =
                     o.GetDouble("orientation_weight", 1.0, 0.0);
                 OrientationOptions r;
                 ReadZoomOutSchedule(o, "orientation_", &r.zoomout);
                 const double descriptor_weight = o.GetDouble("descriptor_weight", 1.0, 0.0);
                 DescriptorMapOptions d;
                 d.k = o.GetInt("descriptor_k", d.k, 2, 1000);
                 d.eigenpairs = o.GetInt("descriptor_eigenpairs", d.eigenpairs, 2, 1000);
                 d.energies = o.GetInt("descriptor_energies", d.energies, 1, 10000);
                 d.sigma = o.GetDouble("descriptor_sigma", d.sigma, 0.0);
                 d.mu = o.GetDouble("descriptor_mu", d.mu, 0.0);
                 d.samples = o.GetInt("descriptor_samples", d.samples, 1, 100000);
                 d.axes = o.GetInt("descriptor_axes", d.axes, 1, 2);
                 const bool refined_on = o.GetBool("refined", true);
                 RefinedAgreementOptions f;
                 ReadZoomOutSchedule(o, "refined_", &f.zoomout);
                 f.margin = o.GetDouble("refined_margin", f.margin, 0.0);
                 f.normal_weight =
                     o.GetDouble("refined_normal_weight", f.normal_weight, 0.0);
                 std::string error;
                 if (!e.IsValid(&error)) o.Fail("", error);
                 if (!r.IsValid(&error)) o.Fail("", "orientation: " + error);
                 if (!d.IsValid(&error)) o.Fail("", "descriptor: " + error);
                 if (!f.IsValid(&error)) o.Fail("", "refined: " + error);
                 return std::make_unique<ExtrinsicStage>(e, orientation_weight, r,
                                                         descriptor_weight, d, refined_on, f);
               });
  registry.Add("flip", "chamfer", "symmetric Chamfer distance of the embeddings only",
               [](OptionReader& o) -> std::unique_ptr<Stage> {
                 return std::make_unique<ChamferStage>(o.GetInt("threads", 1, 0, 256));
               });
  registry.Add("flip", "hks",
               "heat kernel signatures (Laplace-Beltrami eigenpairs) compared through each "
               "candidate's NN map",
               [](OptionReader& o) -> std::unique_ptr<Stage> {
                 HksFlipOptions h;
                 h.eigenpairs = o.GetInt("eigenpairs", h.eigenpairs, 2, 10000);
                 h.num_times = o.GetInt("num_times", h.num_times, 1, 1000);
                 h.threads = o.GetInt("threads", h.threads, 0, 256);
                 return std::make_unique<HksStage>(h);
               });
  registry.Add("flip", "oracle",
               "lowest ground-truth error (evaluation only; fails without ground truth)",
               [](OptionReader& o) -> std::unique_ptr<Stage> {
                 return std::make_unique<OracleStage>(o.GetInt("threads", 1, 0, 256));
               });
}

}  // namespace symembed

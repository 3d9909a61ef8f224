#include "stages/flip/extrinsic_stage.h"

#include <algorithm>
#include <vector>

#include "core/laplacian.h"
#include "stages/flip/decide_refined.h"
#include "stages/flip/extrinsic.h"
#include "stages/flip/flip_term.h"
#include "stages/flip/term_curvature.h"
#include "stages/flip/term_descriptor.h"
#include "stages/flip/term_orientation.h"
#include "stages/flip/term_refined_maps.h"

namespace symembed {
namespace {

// The terms, in the order the stage adds them, with their default weights: the orientation
// term, which skips candidates that cannot win, comes after the terms whose totals it reads.
// By default the rotation is the one whose refined map best preserves the surfaces' intrinsic
// geometry (refined_maps alone): the curvature, descriptor and orientation terms compare
// features that change with the species, the body shape and the meshing, and across species
// their sum picks a wrong rotation where the refined maps' distortion does not. On near
// front-back symmetric bodies (the synthetic humanoids) the refined maps of the right rotation
// and of the one turned by pi about the vertical axis can tie; the other terms and the
// refined_front_back decision remain for such studies.
struct FlipTermEntry {
  const char* name;
  std::unique_ptr<FlipTerm> (*read)(OptionReader& options, double weight);
  double default_weight;
};
const FlipTermEntry kFlipTerms[] = {
    {"curvature", ReadCurvatureTerm, 0.0},
    {"descriptor", ReadDescriptorTerm, 0.0},
    {"refined_maps", ReadRefinedMapsTerm, 1.0},
    {"orientation", ReadOrientationTerm, 0.0},
};

class ArgminDecision : public FlipDecision {
 public:
  int Decide(const FlipTermContext&, const std::array<double, 4>&,
             std::ostringstream*) const override {
    return -1;
  }
};

std::unique_ptr<FlipDecision> ReadArgminDecision(OptionReader&) {
  return std::make_unique<ArgminDecision>();
}

struct FlipDecisionEntry {
  const char* name;
  std::unique_ptr<FlipDecision> (*read)(OptionReader& options);
};
const FlipDecisionEntry kFlipDecisions[] = {
    {"argmin", ReadArgminDecision},
    {"refined_front_back", ReadRefinedDecision},
};

class ExtrinsicStage : public FlipStage {
 public:
  ExtrinsicStage(int threads, std::vector<std::unique_ptr<FlipTerm>> terms,
                 std::unique_ptr<FlipDecision> decision)
      : threads_(threads), terms_(std::move(terms)), decision_(std::move(decision)) {
    basis_size_ = decision_->BasisSize();
    for (const auto& term : terms_) {
      basis_size_ = std::max(basis_size_, term->BasisSize());
      if (term->Features()) features_ = term->Features();
    }
  }

  ShapeNeeds Needs() const override {
    ShapeNeeds needs;
    needs.basis = basis_size_;
    for (const auto& term : terms_) term->AddNeeds(basis_size_, &needs);
    return needs;
  }
  // Whether the decision reads features that no term declares.
  bool LacksFeatures() const { return decision_->ReadsFeatures() && !features_; }

  FlipResult Run(const PairInput& pair) const override {
    CheckFlipPair(pair);
    // One set of candidate maps for every term.
    const CandidateMaps maps = ComputeCandidateMaps(pair.source.Y, pair.target.Y, threads_);
    const Eigen::MatrixXd* Fs =
        features_ ? &ProductOf(pair.source, CurvatureFeaturesKey(*features_)) : nullptr;
    const Eigen::MatrixXd* Ft =
        features_ ? &ProductOf(pair.target, CurvatureFeaturesKey(*features_)) : nullptr;
    // One copy of each basis for all parts, into storage the thread keeps from pair to pair.
    thread_local LaplaceBasis source_basis, target_basis;
    static const LaplaceBasis kNoBasis;
    if (basis_size_ > 0) {
      ShapeBasis(pair.source, basis_size_, &source_basis);
      ShapeBasis(pair.target, basis_size_, &target_basis);
    }
    const LaplaceBasis& source = basis_size_ > 0 ? source_basis : kNoBasis;
    const LaplaceBasis& target = basis_size_ > 0 ? target_basis : kNoBasis;
    const FlipTermContext context{pair, maps, source, target, Fs, Ft, threads_};
    std::array<double, 4> total{};
    std::ostringstream detail;
    for (const auto& term : terms_) term->Score(context, &total, &detail);
    const int chosen = decision_->Decide(context, total, &detail);
    FlipResult result = MakeFlipResult(total, "extrinsic", chosen);
    result.status.message += detail.str();
    return result;
  }

 private:
  int threads_;
  std::vector<std::unique_ptr<FlipTerm>> terms_;  // those of weight > 0, in kFlipTerms order
  std::unique_ptr<FlipDecision> decision_;
  int basis_size_ = 0;  // eigenpairs the parts read (0: none)
  // The smoothing of the curvature features of the context: that of the last term that reads
  // features (none: no term does).
  std::optional<FeatureSmoothing> features_;
};

}  // namespace

std::unique_ptr<FlipStage> ReadExtrinsicStage(OptionReader& o) {
  const int threads = o.GetInt("threads", 1, Range::Closed(0, 256));
  OptionReader terms_options = o.Child("terms");
  std::vector<std::unique_ptr<FlipTerm>> terms;
  for (const FlipTermEntry& entry : kFlipTerms) {
    OptionReader r = terms_options.Child(entry.name);
    const double weight = r.GetDouble("weight", entry.default_weight, Range::AtLeast(0.0));
    std::unique_ptr<FlipTerm> term = entry.read(r, weight);
    r.Finish();
    terms_options.AdoptChild(entry.name, r);
    if (weight > 0.0) terms.push_back(std::move(term));
  }
  terms_options.Finish();
  o.AdoptChild("terms", terms_options);
  if (terms.empty()) terms_options.Fail("", "at least one term must have a weight > 0");

  OptionReader d = o.Child("decide");
  std::vector<std::string> names;
  for (const FlipDecisionEntry& entry : kFlipDecisions) names.push_back(entry.name);
  const std::string type = d.GetChoice("type", "argmin", names);
  std::unique_ptr<FlipDecision> decision;
  for (const FlipDecisionEntry& entry : kFlipDecisions) {
    if (type == entry.name) decision = entry.read(d);
  }
  d.Finish();
  o.AdoptChild("decide", d);
  auto stage = std::make_unique<ExtrinsicStage>(threads, std::move(terms), std::move(decision));
  if (stage->LacksFeatures()) {
    d.Fail("type", "'" + type + "' compares the curvature features, which the curvature and "
                   "refined_maps terms prepare: one of them must have a weight > 0");
  }
  return stage;
}

}  // namespace symembed

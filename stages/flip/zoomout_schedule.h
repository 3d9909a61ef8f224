// The ZoomOut schedule of the flip stage's orientation term and refined decision: the basis sizes
// of the refinement [Melzi et al. 2019] and how many of each shape's samples it runs on and maps
// onto. The options that set it are one YAML map {k_start, k_end, step, samples,
// target_samples}, read by ReadFlipZoomOutSchedule.
#pragma once

#include <string>
#include <vector>

#include "core/fmap/zoomout.h"
#include "core/range.h"
#include "registry/options.h"

namespace symembed {

struct FlipZoomOutSchedule {
  int k_start = 0;  // first basis size
  static constexpr Range kKStart = Range::Closed(1, 1000);
  int k_end = 0;  // last basis size (>= k_start; both bases need k_end eigenpairs)
  static constexpr Range kKEnd = Range::Closed(1, 1000);
  int step = 0;  // basis size increment
  static constexpr Range kStep = Range::Closed(1, 1000);
  // Source samples the iterations run on (the first `samples` of the shape's; >= k_end).
  int samples = 0;
  static constexpr Range kSamples = Range::Closed(1, 100000);
  // Target samples the iterations map onto (the first of the target's; 0: every target vertex).
  int target_samples = 0;
  static constexpr Range kTargetSamples = Range::Closed(0, 100000);

  // The options as the config names them (core/range.h).
  template <typename Self, typename Visit>
  static void Fields(Self& self, Visit&& visit) {
    BasisSizeFields(self, visit);
    visit("samples", self.samples, kSamples);
    visit("target_samples", self.target_samples, kTargetSamples);
  }
  bool IsValid(std::string* error) const;
  // ZoomOut's options for the schedule: the sampled iterations only (dense_result false).
  ZoomOutOptions ZoomOut() const;
  // The target vertices the iterations map onto: the first target_samples of `target_samples`,
  // or none (every target vertex) when target_samples is 0. Throws InvalidInputError "<what> has
  // N samples, fewer than k_end" (SamplePrefix, flip_common.h).
  std::vector<int> TargetPrefix(const std::vector<int>& target_samples,
                                const std::string& what) const;
};

// The schedule in the map `key` of `options` (`defaults` for the keys it does not have), its
// resolved values adopted into options' resolved node. Throws ConfigError (file:line:col and the
// dotted path) for an unknown key, a value out of range or an invalid schedule.
FlipZoomOutSchedule ReadFlipZoomOutSchedule(OptionReader& options, const std::string& key,
                                            const FlipZoomOutSchedule& defaults);

}  // namespace symembed

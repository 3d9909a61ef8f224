#include "stages/flip/zoomout_schedule.h"

#include <sstream>

#include "stages/flip/flip_common.h"

namespace symembed {

bool FlipZoomOutSchedule::IsValid(std::string* error) const {
  std::ostringstream out;
  out << FieldViolation(*this);
  if (out.str().empty() && k_end < k_start) out << "need 1 <= k_start <= k_end";
  if (out.str().empty() && samples < k_end) {
    out << "samples must be >= k_end (" << k_end << "), got " << samples;
  }
  return NoViolation(out.str(), error);
}

ZoomOutOptions FlipZoomOutSchedule::ZoomOut() const {
  ZoomOutOptions zoomout;
  zoomout.k_start = k_start;
  zoomout.k_end = k_end;
  zoomout.step = step;
  // The flip terms read the refined map at the source samples only.
  zoomout.dense_result = false;
  return zoomout;
}

std::vector<int> FlipZoomOutSchedule::TargetPrefix(const std::vector<int>& target_samples,
                                                   const std::string& what) const {
  if (this->target_samples == 0) return {};
  return SamplePrefix(target_samples, this->target_samples, k_end, what);
}

FlipZoomOutSchedule ReadFlipZoomOutSchedule(OptionReader& options, const std::string& key,
                                            const FlipZoomOutSchedule& defaults) {
  OptionReader o = options.Child(key);
  FlipZoomOutSchedule s = defaults;
  ReadFields(o, &s);
  o.Finish();
  RequireValid(o, s);
  options.AdoptChild(key, o);
  return s;
}

}  // namespace symembed

#include "stages/geodesics/geodesics_common.h"

#include <string>

namespace symembed {

bool GeodesicsCommonOptions::IsValid(std::string* error) const {
  if (!kThreads.Contains(threads)) {
    if (error) *error = "threads " + kThreads.Violation(threads) + " (0 = all cores)";
    return false;
  }
  return true;
}

}  // namespace symembed

#include "stages/geodesics/geodesics_common.h"

#include <string>

namespace symembed {

bool GeodesicsCommonOptions::IsValid(std::string* error) const {
  if (threads < 0) {
    if (error) *error = "threads must be >= 0 (0 = all cores), got " + std::to_string(threads);
    return false;
  }
  return true;
}

}  // namespace symembed

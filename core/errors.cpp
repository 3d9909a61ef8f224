#include "core/errors.h"

namespace symembed::detail {

void ThrowCheckFailure(const char* file, int line, const char* cond, const std::string& msg) {
  std::ostringstream out;
  out << file << ":" << line << ": check `" << cond << "` failed";
  if (!msg.empty()) out << ": " << msg;
  throw InternalError(out.str());
}

}  // namespace symembed::detail

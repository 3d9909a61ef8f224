#include "registry/stage_kinds.h"

namespace symembed {

const std::vector<std::string>& PipelineKinds() {
  static const std::vector<std::string> kinds = [] {
    std::vector<std::string> names;
    for (const StageKind& kind : kPipelineStageKinds) names.push_back(kind.name);
    return names;
  }();
  return kinds;
}

const std::vector<std::string>& StageKinds() {
  static const std::vector<std::string> kinds = [] {
    std::vector<std::string> names = PipelineKinds();
    names.push_back(kDatasetKind);
    return names;
  }();
  return kinds;
}

std::string DefaultStageType(const std::string& kind) {
  for (const StageKind& k : kPipelineStageKinds) {
    if (kind == k.name) return k.default_type;
  }
  return "";
}

}  // namespace symembed

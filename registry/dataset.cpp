#include "registry/dataset.h"

#include <algorithm>

namespace symembed {

const DatasetShape* DatasetIndex::Find(const std::string& name) const {
  for (const auto& s : shapes) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

InputGroundTruth PairLines(const ShapeGroundTruth& source, const ShapeGroundTruth& target) {
  InputGroundTruth gt;
  const size_t n = std::min(source.ids.size(), target.ids.size());
  const bool sym = target.sym_ids.size() == target.ids.size();
  for (size_t i = 0; i < n; ++i) {
    if (source.ids[i] < 0 || target.ids[i] < 0) continue;
    if (sym && target.sym_ids[i] < 0) continue;
    gt.source_ids.push_back(source.ids[i]);
    gt.target_ids.push_back(target.ids[i]);
    if (sym) gt.target_sym_ids.push_back(target.sym_ids[i]);
  }
  return gt;
}

}  // namespace symembed

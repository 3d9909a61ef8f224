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

InputGroundTruth PairGroundTruth(const ShapeGroundTruth& source, const std::string& source_name,
                                 const ShapeGroundTruth& target, const std::string& target_name) {
  if (!source.onto.empty() && source.onto == target_name) return source.onto_lines;
  if (!target.onto.empty() && target.onto == source_name) {
    InputGroundTruth reversed;
    reversed.source_ids = target.onto_lines.target_ids;
    reversed.target_ids = target.onto_lines.source_ids;
    return reversed;
  }
  return PairLines(source, target);
}

}  // namespace symembed

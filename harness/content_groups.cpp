#include "harness/content_groups.h"

#include <chrono>
#include <map>
#include <set>

#include "core/errors.h"
#include "core/parallel.h"
#include "harness/shards.h"

namespace symembed {

std::vector<ContentGroup> GroupByContent(const std::vector<std::string>& names,
                                         const DatasetIndex& index, int jobs) {
  std::vector<std::optional<uint64_t>> keys(names.size());
  ParallelFor(
      static_cast<int>(names.size()),
      [&](int i) {
        const DatasetShape* shape = index.Find(names[i]);
        if (!shape) return;
        try {
          keys[i] = MeshKey(shape->mesh_path);
        } catch (const IoError&) {
          // Alone: loading the file fails too, and says why.
        }
      },
      jobs, 1);
  std::vector<ContentGroup> groups;
  std::map<uint64_t, size_t> group_of_key;
  for (size_t i = 0; i < names.size(); ++i) {
    if (keys[i]) {
      const auto [it, added] = group_of_key.emplace(*keys[i], groups.size());
      if (!added) {
        groups[it->second].names.push_back(names[i]);
        continue;
      }
    }
    groups.push_back({{names[i]}, keys[i]});
  }
  return groups;
}

std::vector<ContentGroup> ContentGroupsOfShard(const std::vector<std::string>& sorted_names,
                                               const DatasetIndex& dataset, int index, int count,
                                               int jobs) {
  const std::vector<std::string> mine = ShapesOfShard(sorted_names, index, count);
  const std::set<std::string> firsts(mine.begin(), mine.end());
  std::vector<ContentGroup> groups;
  for (ContentGroup& group : GroupByContent(sorted_names, dataset, jobs)) {
    if (firsts.count(group.names.front())) groups.push_back(std::move(group));
  }
  return groups;
}

std::string FailureNamingFile(const std::string& message, const std::string& computed_path,
                              const std::string& path) {
  if (!computed_path.empty() && message.compare(0, computed_path.size(), computed_path) == 0) {
    return path + message.substr(computed_path.size());
  }
  return path + ": " + message;
}

std::vector<NamedOutcome> ComputeContentGroup(const ContentGroup& group, const DatasetIndex& index,
                                              const Pipeline& pipeline, const MeshLoader& load_mesh,
                                              const ShapeContext& context) {
  const size_t n = group.names.size();
  std::vector<NamedOutcome> results(n);
  std::vector<const DatasetShape*> shapes(n);
  for (size_t k = 0; k < n; ++k) shapes[k] = index.Find(group.names[k]);
  const DatasetShape* first = shapes[0];
  if (!first) {
    results[0].failure = "no shape '" + group.names[0] + "' in the dataset";
    return results;
  }
  // Every name still without an outcome or a failure fails with `message`, from work on the
  // file `computed_path`.
  auto fail_rest = [&](const std::string& message, const std::string& computed_path) {
    for (size_t k = 0; k < n; ++k) {
      if (!results[k].outcome && results[k].failure.empty()) {
        results[k].failure = FailureNamingFile(message, computed_path, shapes[k]->mesh_path);
      }
    }
  };

  Surface input;
  const auto start = std::chrono::steady_clock::now();
  try {
    input = load_mesh(first->mesh_path);
  } catch (const std::exception& e) {
    fail_rest(e.what(), first->mesh_path);
    return results;
  }
  const double load_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // The ground truth is each name's own, read before anything is computed as for a shape alone.
  std::vector<ShapeGroundTruth> truths(n);
  std::vector<size_t> pending;
  for (size_t k = 0; k < n; ++k) {
    try {
      truths[k] = pipeline.dataset->GroundTruth(*shapes[k], input.NumVertices());
      pending.push_back(k);
    } catch (const std::exception& e) {
      results[k].failure = FailureNamingFile(e.what(), shapes[k]->mesh_path, shapes[k]->mesh_path);
    }
  }
  if (pending.empty()) return results;

  const DatasetShape& computed = *shapes[pending.front()];
  ShapeOutcome content;
  try {
    const uint64_t mesh_key = group.mesh_key ? *group.mesh_key : MeshKey(computed.mesh_path);
    content = ComputeMeshOutcome(std::move(input), load_seconds, mesh_key, pipeline, context);
  } catch (const std::exception& e) {
    fail_rest(e.what(), computed.mesh_path);
    return results;
  }
  for (size_t j = 0; j < pending.size(); ++j) {
    const size_t k = pending[j];
    NamedOutcome& result = results[k];
    result.reused = j > 0;
    if (result.reused) result.computed_with = computed.name;
    try {
      // The last name takes the content itself, the others a copy.
      ShapeOutcome outcome =
          j + 1 == pending.size()
              ? OutcomeOfShape(std::move(content), *shapes[k], std::move(truths[k]), result.reused)
              : OutcomeOfShape(content, *shapes[k], std::move(truths[k]), result.reused);
      result.outcome = std::make_unique<ShapeOutcome>(std::move(outcome));
    } catch (const std::exception& e) {
      result.failure = FailureNamingFile(e.what(), shapes[k]->mesh_path, shapes[k]->mesh_path);
    }
  }
  return results;
}

}  // namespace symembed

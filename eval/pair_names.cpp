#include "eval/pair_names.h"

#include "core/errors.h"

namespace symembed {

std::string PlainPairStem(const std::string& source, const std::string& target) {
  return source + "_" + target;
}

std::string EscapedPairStem(const std::string& source, const std::string& target) {
  std::string stem;
  for (char c : source) {
    if (c == '%') {
      stem += "%25";
    } else if (c == '_') {
      stem += "%5F";
    } else {
      stem += c;
    }
  }
  return stem + "_" + target;
}

PairNames::PairNames(const std::vector<DatasetPair>& pairs) {
  for (const DatasetPair& p : pairs) names_.emplace(std::make_pair(p.source, p.target), Name());
  // Counted over distinct pairs, so that a pair listed twice does not collide with itself.
  std::map<std::string, int> plain_count;
  for (const auto& [pair, name] : names_) ++plain_count[PlainPairStem(pair.first, pair.second)];
  for (auto& [pair, name] : names_) {
    const std::string plain = PlainPairStem(pair.first, pair.second);
    name.escaped = plain_count[plain] > 1 || plain.find('%') != std::string::npos;
    name.stem = name.escaped ? EscapedPairStem(pair.first, pair.second) : plain;
  }
}

const PairNames::Name& PairNames::Find(const std::string& source, const std::string& target) const {
  const auto it = names_.find({source, target});
  SYMEMBED_CHECK(it != names_.end(),
                 "the pair " << source << " -> " << target << " is not in the list of names");
  return it->second;
}

const std::string& PairNames::Stem(const std::string& source, const std::string& target) const {
  return Find(source, target).stem;
}

bool PairNames::Escaped(const std::string& source, const std::string& target) const {
  return Find(source, target).escaped;
}

}  // namespace symembed

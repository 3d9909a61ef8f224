// The file stem of each pair of a list: its map maps/STEM.map and record pairs/STEM.rec in a
// variant folder, a map STEM.map of a folder `symembed eval` scores, and its `name` in
// timings.csv.
//
// The plain stem "A_B" (source, '_', target) is ambiguous when names hold '_': the pairs
// p_q1 -> r1 and p -> q1_r1 are both "p_q1_r1". A pair keeps its plain stem when that is unique
// among the plain stems of the list and holds no '%', so every dataset without such a
// collision (FAUST's tr_reg_000_tr_reg_001 among them) keeps the names it always had. Every
// other pair gets the escaped stem Esc(A) + "_" + B, where Esc writes '%' as "%25" and '_' as
// "%5F": p%5Fq1_r1 and p_q1_r1 above.
//
// Distinct pairs of the list get distinct stems:
//   two escaped stems: Esc(A) holds no '_', so the first '_' is the separator, and Esc is
//     injective, so the stem gives back A and B;
//   two plain stems: only unique plain stems are used;
//   a plain stem s of pair X and the escaped stem of pair Y: s holds no '%', so neither does
//     the escaped stem, hence Y's source holds no '_' or '%' and its escaped stem is its plain
//     stem, which is not X's unique plain stem.
//
// A stem depends on the whole list, so writers and readers of one folder must build the names
// from the same list: the variant's pairs before sharding (every shard and the merge agree),
// the dataset's pairs for `symembed eval`, a folder's pairs.csv rows for its timings.csv.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "registry/dataset.h"

namespace symembed {

class PairNames {
 public:
  PairNames() = default;
  // pairs: the list; a pair given twice is one pair.
  explicit PairNames(const std::vector<DatasetPair>& pairs);

  // The stem of a pair of the list. Throws InternalError for a pair not in it (its stem could
  // be another pair's).
  const std::string& Stem(const std::string& source, const std::string& target) const;
  // Whether the pair has the escaped stem: its plain stem is another pair's too, or holds '%'.
  // (The two may be the same text: p -> q1_r1 above.) Throws as Stem.
  bool Escaped(const std::string& source, const std::string& target) const;

 private:
  struct Name {
    std::string stem;
    bool escaped = false;
  };
  const Name& Find(const std::string& source, const std::string& target) const;
  std::map<std::pair<std::string, std::string>, Name> names_;
};

// "A_B".
std::string PlainPairStem(const std::string& source, const std::string& target);
// Esc(A) + "_" + B, Esc as above.
std::string EscapedPairStem(const std::string& source, const std::string& target);

}  // namespace symembed

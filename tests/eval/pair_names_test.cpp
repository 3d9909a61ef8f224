#include "eval/pair_names.h"

#include <gtest/gtest.h>

#include <random>
#include <set>

#include "core/errors.h"

namespace symembed {
namespace {

// Every name of 1 to max_length characters from the alphabet.
std::vector<std::string> AllNames(const std::string& alphabet, int max_length) {
  std::vector<std::string> names;
  std::vector<std::string> last = {""};
  for (int length = 1; length <= max_length; ++length) {
    std::vector<std::string> next;
    for (const std::string& prefix : last) {
      for (char c : alphabet) next.push_back(prefix + c);
    }
    names.insert(names.end(), next.begin(), next.end());
    last = next;
  }
  return names;
}

std::vector<DatasetPair> AllPairs(const std::vector<std::string>& names) {
  std::vector<DatasetPair> pairs;
  for (const std::string& a : names) {
    for (const std::string& b : names) pairs.push_back({a, b});
  }
  return pairs;
}

// The number of distinct stems the names give the pairs (the list holds no pair twice).
size_t DistinctStems(const std::vector<DatasetPair>& pairs) {
  const PairNames names(pairs);
  std::set<std::string> stems;
  for (const DatasetPair& p : pairs) stems.insert(names.Stem(p.source, p.target));
  return stems.size();
}

TEST(PairNames, UniquePlainStemsAreKeptEvenWithUnderscores) {
  const PairNames names({{"tr_reg_000", "tr_reg_001"}, {"tr_reg_001", "tr_reg_000"}, {"a", "b"}});
  EXPECT_EQ(names.Stem("tr_reg_000", "tr_reg_001"), "tr_reg_000_tr_reg_001");
  EXPECT_EQ(names.Stem("tr_reg_001", "tr_reg_000"), "tr_reg_001_tr_reg_000");
  EXPECT_EQ(names.Stem("a", "b"), "a_b");
  EXPECT_FALSE(names.Escaped("tr_reg_000", "tr_reg_001"));
  EXPECT_FALSE(names.Escaped("a", "b"));
}

TEST(PairNames, PairsWhosePlainStemsCollideGetEscapedStems) {
  const PairNames names({{"p_q1", "r1"}, {"p", "q1_r1"}, {"r1", "p"}});
  EXPECT_EQ(names.Stem("p_q1", "r1"), "p%5Fq1_r1");
  EXPECT_EQ(names.Stem("p", "q1_r1"), "p_q1_r1");
  EXPECT_TRUE(names.Escaped("p_q1", "r1"));
  EXPECT_TRUE(names.Escaped("p", "q1_r1"));
  // The others keep theirs.
  EXPECT_EQ(names.Stem("r1", "p"), "r1_p");
  EXPECT_FALSE(names.Escaped("r1", "p"));
}

TEST(PairNames, NamesWithPercentAreEscaped) {
  const PairNames names({{"50%", "b"}, {"a", "5%"}, {"a%5F", "b"}, {"a_", "b"}});
  EXPECT_EQ(names.Stem("50%", "b"), "50%25_b");
  EXPECT_EQ(names.Stem("a", "5%"), "a_5%");  // the escaped stem: the source has nothing to escape
  EXPECT_TRUE(names.Escaped("a", "5%"));
  // The plain stem of a%5F -> b is the escaped stem of a_ -> b; neither is used here.
  EXPECT_EQ(names.Stem("a%5F", "b"), "a%255F_b");
  EXPECT_EQ(names.Stem("a_", "b"), "a__b");
}

// _ -> _q and __ -> q collide (___q), so the first is escaped to %5F__q: the plain stem of
// %5F -> _q, which must therefore not be used.
TEST(PairNames, AnEscapedStemIsNeverAPlainStemWithPercent) {
  const PairNames names({{"_", "_q"}, {"__", "q"}, {"%5F", "_q"}});
  EXPECT_EQ(names.Stem("_", "_q"), "%5F__q");
  EXPECT_EQ(names.Stem("__", "q"), "%5F%5F_q");
  EXPECT_EQ(names.Stem("%5F", "_q"), "%255F__q");
}

TEST(PairNames, APairListedTwiceIsOnePair) {
  const PairNames names({{"a_b", "c"}, {"x", "y"}, {"a_b", "c"}});
  EXPECT_EQ(names.Stem("a_b", "c"), "a_b_c");
  EXPECT_FALSE(names.Escaped("a_b", "c"));
}

TEST(PairNames, APairNotInTheListHasNoStem) {
  const PairNames names(std::vector<DatasetPair>{{"a", "b"}});
  EXPECT_THROW(names.Stem("b", "a"), InternalError);
  EXPECT_THROW(PairNames().Stem("a", "b"), InternalError);
}

// Every pair of names of up to 3 characters from {p, q, _, %, 5, F} (258 names; with 5 and F a
// name can spell an escape, as %5F does) in one list; random sublists (seeded) of the pairs of
// names of up to 2 characters; and every list of two pairs of names of up to 2 characters from
// {p, q, _, %}.
TEST(PairNames, DistinctPairsGetDistinctStemsOverAllShortNames) {
  const std::vector<DatasetPair> all = AllPairs(AllNames("pq_%5F", 3));
  ASSERT_EQ(all.size(), 258u * 258u);
  EXPECT_EQ(DistinctStems(all), all.size());

  const std::vector<DatasetPair> short_pairs = AllPairs(AllNames("pq_%5F", 2));
  std::mt19937 random(7);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<DatasetPair> some;
    std::set<std::pair<std::string, std::string>> seen;
    for (int k = 0; k < 30; ++k) {
      const DatasetPair& p = short_pairs[random() % short_pairs.size()];
      if (seen.insert({p.source, p.target}).second) some.push_back(p);
    }
    EXPECT_EQ(DistinctStems(some), some.size()) << "trial " << trial;
  }

  const std::vector<DatasetPair> pairs = AllPairs(AllNames("pq_%", 2));
  int collisions = 0;  // lists where the plain stems collide: the case that needs escaping
  for (size_t i = 0; i < pairs.size(); ++i) {
    for (size_t j = i + 1; j < pairs.size(); ++j) {
      const std::vector<DatasetPair> two = {pairs[i], pairs[j]};
      ASSERT_EQ(DistinctStems(two), 2u) << pairs[i].source << " -> " << pairs[i].target << ", "
                                        << pairs[j].source << " -> " << pairs[j].target;
      collisions += PlainPairStem(pairs[i].source, pairs[i].target) ==
                    PlainPairStem(pairs[j].source, pairs[j].target);
    }
  }
  EXPECT_GT(collisions, 0);
}

}  // namespace
}  // namespace symembed

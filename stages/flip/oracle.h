// Flip scorer `oracle`: the candidate with the lowest ground-truth error (evaluation only; the
// upper bound of every other scorer).
//
// For candidate k the score is the mean Euclidean distance, on the target surface (in units of
// sqrt(target area)), between the image of each ground-truth source vertex under the
// candidate's nearest-neighbour map and its ground-truth target vertex: a cheap proxy of the
// geodesic error, adequate to rank the four candidates.
#pragma once

#include <array>

#include "registry/types.h"

namespace symembed {

// Throws InvalidInputError when pair.ground_truth is null or empty or its ids are out of range.
std::array<double, 4> OracleFlipScores(const PairInput& pair, int threads = 1);

}  // namespace symembed

// Fuzz target of the pairs file reader (test_pairs.txt; eval/datasets/dataset_files.h
// ParsePairsText).
#include <cstdlib>

#include "core/errors.h"
#include "eval/datasets/dataset_files.h"
#include "fuzz/fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    for (const symembed::PairLine& p :
         symembed::ParsePairsText(symembed::fuzz::Text(data, size), "fuzz_pairs.txt")) {
      if (p.source.empty() || p.target.empty() || p.line < 1) std::abort();
    }
  } catch (const symembed::Error&) {
  }
  return 0;
}

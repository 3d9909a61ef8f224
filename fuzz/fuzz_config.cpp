// Fuzz target of the experiment config parser (harness/config.h ParseExperimentConfig) with
// every built-in stage registered: YAML syntax, strict options, variants, ${VAR} substitution.
// Parsing builds every variant's pipeline (stages are constructed, nothing runs).
#include "core/errors.h"
#include "fuzz/fuzz_target.h"
#include "harness/config.h"
#include "registry/registry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const symembed::Registry* registry = [] {
    auto* r = new symembed::Registry;
    symembed::RegisterBuiltinStages(*r);
    return r;
  }();
  try {
    symembed::ParseExperimentConfig(symembed::fuzz::Text(data, size), "fuzz.yaml", *registry);
  } catch (const symembed::Error&) {
  }
  return 0;
}

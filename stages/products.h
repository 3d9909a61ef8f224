// The cache format of per-shape products (registry/shape_products.h) whose types the stages
// define, beside registry/serialize.h's for the harness's own types.
#pragma once

#include "registry/serialize.h"
#include "stages/flip/descriptor_map.h"

namespace symembed {

void Write(ArchiveWriter& out, const WksProducts& products);
void Read(ArchiveReader& in, WksProducts* products);

}  // namespace symembed

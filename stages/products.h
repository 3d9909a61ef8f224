// The cache format of per-shape products (registry/shape_products.h) whose types the stages
// define, beside registry/serialize.h's for the harness's own types.
#pragma once

#include "core/fmap/descriptors.h"
#include "registry/serialize.h"

namespace symembed {

void Write(ArchiveWriter& out, const WksProducts& products);
void Read(ArchiveReader& in, WksProducts* products);

}  // namespace symembed

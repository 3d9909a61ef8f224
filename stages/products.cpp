#include "stages/products.h"

namespace symembed {

void Write(ArchiveWriter& out, const WksProducts& products) {
  out.Matrix(products.P);
  out.Matrix(products.Q);
}

void Read(ArchiveReader& in, WksProducts* products) {
  products->P = in.Matrix();
  products->Q = in.Matrix();
}

}  // namespace symembed

// Forward declarations of the FLANN kd-tree index held by KnnIndex (core/knn.h) and
// SpectralNearest (core/fmap/spectral_knn.h), so that their headers need not include FLANN;
// their .cpp files include <flann/flann.hpp>.
#pragma once

#include <memory>

namespace flann {
template <typename T>
struct L2;
template <typename Distance>
class Index;
}  // namespace flann

namespace symembed {

// An exact single kd-tree over double-precision points under the (squared) L2 distance.
using FlannL2Index = flann::Index<flann::L2<double>>;

}  // namespace symembed

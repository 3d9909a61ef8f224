#include "eval/datasets/register.h"

#include "eval/datasets/kim2011.h"
#include "eval/datasets/pairs_vts.h"
#include "eval/datasets/remeshed_dataset.h"
#include "eval/datasets/same_connectivity.h"
#include "eval/datasets/shrec16.h"
#include "eval/datasets/synthetic_dataset.h"

namespace symembed {

void RegisterDatasetLoaders(Registry& registry) {
  registry.Add("dataset", "pairs_vts",
               "shapes/*.off|obj|ply + corres/NAME.vts (.sym.vts) + test_pairs.txt (TOSCA/FAUST "
               "remeshed, synthetic output); optionally read through an independent, "
               "optionally anisotropic remeshing of every shape (cached)",
               [](OptionReader& o) { return CreatePairsVtsDataset(o); });
  registry.Add("dataset", "same_connectivity",
               "root/<class>/*.off|obj|ply sharing vertex ids (SCAPE, TOSCA originals); "
               "identity ground truth, optional sym.txt",
               [](OptionReader& o) {
                 return std::make_unique<SameConnectivityDataset>(ReadSameConnectivityOptions(o));
               });
  registry.Add("dataset", "kim2011",
               "the Kim et al. 2011 benchmark as distributed: Data/<SET>/Meshes, Corrs/*.pid|"
               "*.vts landmarks and *.sym.info mirrors, Results/Corr_*.query",
               [](OptionReader& o) { return std::make_unique<Kim2011Dataset>(ReadKim2011Options(o)); });
  registry.Add("dataset", "shrec16_partial",
               "SHREC'16 partial matching as distributed: null/CLASS.off + cuts|holes/"
               "TRACK_CLASS_shape_N.off with .baryc_gt (.baryc_gt_sym); each partial shape onto "
               "its class's null shape",
               [](OptionReader& o) {
                 return std::make_unique<Shrec16PartialDataset>(ReadShrec16PartialOptions(o));
               });
  registry.Add("dataset", "topkids",
               "SHREC'16 topological noise (TOPKIDS) as distributed: kidNN.off + kidNN_ref.txt; "
               "each kid onto the null shape kid00",
               [](OptionReader& o) { return std::make_unique<TopKidsDataset>(ReadTopKidsOptions(o)); });
  registry.Add("dataset", "synthetic",
               "generated symmetric articulated figures with exact ground truth (cached, read "
               "as pairs_vts)",
               [](OptionReader& o) { return CreateSyntheticDataset(o); });
}

}  // namespace symembed

#include "registry/product_needs.h"

#include <gtest/gtest.h>

#include "core/errors.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

// A product of the surface: its vertex count times `factor`, counting its computations.
ProductKey<Eigen::MatrixXd> ScaledCountKey(int factor) {
  return {"scaled_count", "factor=" + std::to_string(factor)};
}

ProductNeed ScaledCountNeed(int factor, int* computed) {
  return NeedProduct(ScaledCountKey(factor), ProductInput::kSurface, 0,
                     [factor, computed](const ShapeData& shape, const LaplaceBasis&) {
                       ++*computed;
                       return Eigen::MatrixXd::Constant(1, 1, factor * shape.surface.NumVertices());
                     });
}

// A product of the basis of `size` eigenpairs: its eigenvalues.
ProductKey<Eigen::MatrixXd> EigenvaluesKey() { return {"eigenvalues", ""}; }

ProductNeed EigenvaluesNeed(int size) {
  return NeedProduct(EigenvaluesKey(), ProductInput::kBasis, size,
                     [](const ShapeData&, const LaplaceBasis& basis) {
                       return Eigen::MatrixXd(basis.evals);
                     });
}

ShapeData Blob() {
  ShapeData shape;
  shape.name = "blob";
  shape.surface = testing::BumpyBlob(6);
  return shape;
}

TEST(ShapeNeeds, AddKeepsTheLargerBasisAndEachProductOnce) {
  int computed = 0;
  ShapeNeeds needs;
  needs.basis = 8;
  needs.products.push_back(ScaledCountNeed(2, &computed));
  ShapeNeeds other;
  other.basis = 12;
  other.products.push_back(ScaledCountNeed(2, &computed));
  other.products.push_back(ScaledCountNeed(3, &computed));
  needs.Add(other);
  EXPECT_EQ(needs.basis, 12);
  ASSERT_EQ(needs.products.size(), 2u);
  EXPECT_EQ(needs.products[0].id, "scaled_count{factor=2}");
  EXPECT_EQ(needs.products[1].id, "scaled_count{factor=3}");
  ShapeNeeds none;
  needs.Add(none);
  EXPECT_EQ(needs.basis, 12);
}

TEST(ComputeNeeds, ComputesTheBasisAndEachProductOnceAndTypesThem) {
  ShapeData shape = Blob();
  int computed = 0;
  ShapeNeeds needs;
  needs.basis = 10;
  needs.products.push_back(ScaledCountNeed(2, &computed));
  ComputeNeeds(needs, &shape);
  EXPECT_EQ(shape.basis.NumEigenpairs(), 10);
  EXPECT_EQ(ProductOf(shape, ScaledCountKey(2))(0, 0), 2.0 * shape.surface.NumVertices());
  EXPECT_EQ(computed, 1);
  // A product already there is not computed again; a smaller basis leaves the larger one.
  const Eigen::MatrixXd evecs = shape.basis.evecs;
  needs.basis = 5;
  ComputeNeeds(needs, &shape);
  EXPECT_EQ(computed, 1);
  EXPECT_EQ(shape.basis.evecs, evecs);
  // Missing, or read as another type: an error naming the shape and the product.
  try {
    ProductOf(shape, ScaledCountKey(3));
    FAIL() << "no error";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("shape 'blob' has no product 'scaled_count{factor=3}'"),
              std::string::npos)
        << e.what();
  }
  const ProductKey<std::vector<int>> wrong_type{"scaled_count", "factor=2"};
  EXPECT_THROW(ProductOf(shape, wrong_type), InvalidInputError);
  // The shape's basis read beyond what was declared.
  LaplaceBasis basis;
  ShapeBasis(shape, 10, &basis);
  EXPECT_EQ(basis.evecs, evecs);
  EXPECT_THROW(ShapeBasis(shape, 11, &basis), InvalidInputError);
  EXPECT_EQ(&ShapeBasisWithAtLeast(shape, 10), &shape.basis);
  EXPECT_EQ(&ShapeBasisWithAtLeast(shape, 4), &shape.basis);
  EXPECT_THROW(ShapeBasisWithAtLeast(shape, 11), InvalidInputError);
}

TEST(ComputeNeeds, AProductOfABasisOfAnotherSizeIsComputedFromThatBasis) {
  ShapeData shape = Blob();
  ShapeNeeds needs;
  needs.basis = 12;
  needs.products.push_back(EigenvaluesNeed(6));
  ComputeNeeds(needs, &shape);
  EXPECT_EQ(shape.basis.NumEigenpairs(), 12);
  LaplaceBasisOptions six;
  six.k = 6;
  const Eigen::MatrixXd& evals = ProductOf(shape, EigenvaluesKey());
  EXPECT_EQ(evals, Eigen::MatrixXd(ComputeLaplaceBasis(shape.surface, six).evals));
}

TEST(NeedProduct, StoresAndReadsBackItsValue) {
  int computed = 0;
  const ProductNeed need = ScaledCountNeed(4, &computed);
  ShapeData shape = Blob();
  const std::any value = need.compute(shape, LaplaceBasis{});
  ArchiveWriter out;
  need.write(out, value);
  ArchiveReader in(out.Finish("scaled_count"), "scaled_count");
  const std::any back = need.read(in);
  in.ExpectEnd();
  EXPECT_EQ(*std::any_cast<Eigen::MatrixXd>(&back), *std::any_cast<Eigen::MatrixXd>(&value));
}

}  // namespace
}  // namespace symembed

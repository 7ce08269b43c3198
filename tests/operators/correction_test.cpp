#include "sphstab/operators/correction.hpp"

#include <gtest/gtest.h>

#include "correction_fixture.hpp"
#include "sphstab/operators/column_shepard.hpp"
#include "sphstab/operators/mean_polish.hpp"
#include "sphstab/operators/minus_gradient.hpp"
#include "sphstab/operators/ncsph.hpp"

namespace sphstab {
namespace correction_test {

using test::Complex;
using test::make_case;

TEST(Correction, NamesRoundTrip) {
  EXPECT_EQ(all_corrections().size(), 8u);
  for (Correction c : all_corrections()) EXPECT_EQ(parse_correction(correction_name(c)), c);
  try {
    parse_correction("shepherd");
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("shepherd"), std::string::npos);
    EXPECT_NE(msg.find("shepard-column-polish"), std::string::npos) << msg;  // lists the valid names
  }
  EXPECT_TRUE(correction_is_dense(Correction::MeanPolish));
  EXPECT_FALSE(correction_is_dense(Correction::Ncsph));
}

double diff(const SparseMatrix<>& a, const SparseMatrix<>& b) {
  return (Eigen::MatrixXd(a) - Eigen::MatrixXd(b)).cwiseAbs().maxCoeff();
}

template <int Dim>
void expect_dispatch(LatticeType type, int n) {
  auto c = make_case<Dim>(type, n, 1.3, 0.15, false);
  Eigen::VectorXd counts = neighbour_counts(c.set, c.nl, NeighbourCounting::Actual);
  auto ncsph = ncsph_gradient<Dim, double>(c.set, c.ops.W, c.ops.G);
  for (Correction corr : all_corrections()) {
    auto g = apply_correction<Dim, double>(corr, c.set, c.nl, c.ops);
    auto gc = apply_correction<Dim, Complex>(corr, c.set, c.nl, c.cops);
    for (int a = 0; a < Dim; ++a) {
      SparseMatrix<> expected;
      switch (corr) {
        case Correction::None:
          expected = c.ops.G[a];
          break;
        case Correction::Minus:
          expected = minus_gradient(c.ops.G[a]);
          break;
        case Correction::Shepard:
          expected = shepard_gradient(c.ops.W, c.ops.G[a]);
          break;
        case Correction::ColumnShepard:
          expected = column_shepard_gradient(c.ops.W, c.ops.G[a]);
          break;
        case Correction::Ncsph:
          expected = ncsph[a];
          break;
        case Correction::LocalPolish:
          expected = local_polish(c.ops.G[a], counts);
          break;
        case Correction::MeanPolish:
          expected = mean_polish(c.ops.G[a]).sparseView(0.0, 0.0);
          break;
        case Correction::ShepardColumnPolish:
          expected = shepard_column_polish(c.ops.W, c.ops.G[a]).sparseView(0.0, 0.0);
          break;
      }
      EXPECT_EQ(diff(g[a], expected), 0.0) << correction_name(corr);
      EXPECT_LT(test::complex_mismatch(g[a], gc[a]), 1e-15) << correction_name(corr);
      if (correction_is_dense(corr)) EXPECT_EQ(g[a].nonZeros(), static_cast<long>(c.set.size()) * c.set.size());
    }
  }
}

TEST(Correction, DispatchMatchesTheFunctionsForBothScalars) {
  expect_dispatch<1>(LatticeType::Line, 12);
  expect_dispatch<2>(LatticeType::Square, 4);
}

TEST(Correction, OptionsAreApplied) {
  auto c = make_case<2>(LatticeType::Square, 5, 1.3, 0.1, false, 0);
  CorrectionOptions<2> level{.counting = NeighbourCounting::BoundaryLevel};
  auto g = apply_correction<2, double>(Correction::LocalPolish, c.set, c.nl, c.ops, level);
  EXPECT_EQ(diff(g[1], local_polish(c.ops.G[1], neighbour_counts(c.set, c.nl, NeighbourCounting::BoundaryLevel))), 0.0);
  std::array<ShepardReference, 2> ref{shepard_reference(c.ops.W, c.ops.G[0]), shepard_reference(c.ops.W, c.ops.G[1])};
  CorrectionOptions<2> first_step{.reference = &ref};
  g = apply_correction<2, double>(Correction::LocalPolish, c.set, c.nl, c.ops, first_step);
  Eigen::VectorXd counts = neighbour_counts(c.set, c.nl, NeighbourCounting::Actual);
  EXPECT_EQ(diff(g[0], local_polish(c.ops.G[0], local_means(shepard_gradient(c.ops.W, c.ops.G[0]), counts))), 0.0);

  auto f = make_case<2>(LatticeType::Square, 4, 1.3, 0.1, false);
  CorrectionOptions<2> free_only{.polish_free_only = true};
  g = apply_correction<2, double>(Correction::MeanPolish, f.set, f.nl, f.ops, free_only);
  EXPECT_EQ(diff(g[0], mean_polish(f.ops.G[0], f.set.indices(Role::Free)).sparseView(0.0, 0.0)), 0.0);
}

TEST(Correction, RejectsBadInput) {
  auto c = make_case<2>(LatticeType::Square, 4, 1.3, 0.1, false);
  CorrectionOptions<2> free_only{.polish_free_only = true};
  EXPECT_THROW((apply_correction<2, double>(Correction::Shepard, c.set, c.nl, c.ops, free_only)),
               std::invalid_argument);
  CorrectionOptions<2> level{.counting = NeighbourCounting::BoundaryLevel};
  EXPECT_THROW((apply_correction<2, double>(Correction::Minus, c.set, c.nl, c.ops, level)), std::invalid_argument);
  Operators<2, double> no_w = c.ops;
  no_w.W = SparseMatrix<>();
  EXPECT_THROW((apply_correction<2, double>(Correction::Ncsph, c.set, c.nl, no_w)), std::invalid_argument);
  EXPECT_NO_THROW((apply_correction<2, double>(Correction::Minus, c.set, c.nl, no_w)));
  auto d = make_case<2>(LatticeType::Square, 3, 1.3, 0.1, false);
  EXPECT_THROW((apply_correction<2, double>(Correction::Minus, d.set, d.nl, c.ops)), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab

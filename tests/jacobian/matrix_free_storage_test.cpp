// MatrixFreeLinearisation's two storages against each other: the values of G and H per pair (PerPair, the route every
// other test checks against the assembled Jacobian) and once per lattice offset with lattice loops (ByOffset, header
// comment of matrix_free_linearisation.hpp). Both sum the same terms in another order, so they agree to round-off and
// not bitwise; the critical strain through matrix_free_critical_load must come out the same from both.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cstring>
#include <iostream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "sphstab/core/simd_dispatch.hpp"
#include "sphstab/core/threads.hpp"
#include "sphstab/jacobian/matrix_free_linearisation.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/stability/lattice_sine_preconditioner.hpp"
#include "sphstab/stability/lattice_stencil.hpp"
#include "sphstab/stability/matrix_free_critical_load.hpp"
#include "vector_comparison.hpp"

namespace sphstab {
namespace matrix_free_storage_test {

const ElasticMaterial kMaterial = ElasticMaterial::from_lame(1.2115384615384615, 0.8076923076923077, 7.8);

template <int Dim>
std::shared_ptr<const Discretisation<Dim>> lattice(int n, KernelType kernel, double h, LatticeOptions opt = {}) {
  const Kernel<Dim> k(kernel);
  opt.support_radius = k.support_radius(h);
  return make_discretisation(make_lattice<Dim>(Dim == 2 ? LatticeType::Square : LatticeType::Cubic, n, opt), k, h);
}

using test::random_vector;
using test::relative_difference;

/// Largest relative difference of ByOffset from PerPair over every form, both pre-strain kinds and A0, A1, A(load),
/// c0 A0 + c1 A1 on random vectors; checks the flags and the storage each reports.
template <int Dim>
double worst_storage_difference(const Discretisation<Dim>& d, const std::string& name) {
  double worst = 0;
  for (MomentumForm form : all_momentum_forms())
    for (PreStrainKind kind : {PreStrainKind::Isotropic, PreStrainKind::UniaxialX}) {
      const std::string what = name + " " + momentum_form_name(form) + " " + prestrain_kind_name(kind);
      const MatrixFreeLinearisation<Dim> pair(d, kMaterial, form, kind, MatrixFreeStorage::PerPair);
      const MatrixFreeLinearisation<Dim> offset(d, kMaterial, form, kind, MatrixFreeStorage::ByOffset);
      const MatrixFreeLinearisation<Dim> automatic(d, kMaterial, form, kind);
      EXPECT_EQ(pair.storage(), MatrixFreeStorage::PerPair) << what;
      EXPECT_EQ(offset.storage(), MatrixFreeStorage::ByOffset) << what;
      EXPECT_EQ(automatic.storage(), MatrixFreeStorage::ByOffset) << what;
      EXPECT_EQ(offset.symmetric(), pair.symmetric()) << what;
      EXPECT_EQ(offset.complete(), pair.complete()) << what;
      EXPECT_EQ(offset.free_index(), pair.free_index()) << what;
      for (int trial = 0; trial < 2; ++trial) {
        const Eigen::VectorXd x = random_vector(pair.dofs(), 100 * trial + 7);
        Eigen::VectorXd p(pair.dofs()), q(pair.dofs());
        const auto compare = [&](const char* op) {
          const double diff = relative_difference(q, p);
          // O(100) terms of size max |A| |x| summed in another order: round-off only.
          EXPECT_LE(diff, 1e-13) << what << " " << op;
          worst = std::max(worst, diff);
        };
        pair.apply_A0(x, p);
        offset.apply_A0(x, q);
        compare("A0");
        pair.apply_A1(x, p);
        offset.apply_A1(x, q);
        if (form == MomentumForm::Minus) {
          EXPECT_EQ(q.cwiseAbs().maxCoeff(), 0.0) << what;
        } else {
          compare("A1");
        }
        pair.apply(-0.3, x, p);
        offset.apply(-0.3, x, q);
        compare("A(-0.3)");
        pair.apply_combination(0.5, 2.0, x, p);
        offset.apply_combination(0.5, 2.0, x, q);
        compare("0.5 A0 + 2 A1");
      }
    }
  return worst;
}

TEST(MatrixFreeStorage, ByOffsetAgreesWithPerPairIn2D) {
  double worst = std::max(
      {worst_storage_difference(*lattice<2>(9, KernelType::CubicSpline, 1.3), "square 9 cubic spline h 1.3"),
       worst_storage_difference(*lattice<2>(8, KernelType::QuinticSpline, 1.2), "square 8 quintic h 1.2"),
       // a radius beyond the support: offsets with G = H = 0 in the set, the same on both sides
       worst_storage_difference(*make_discretisation(make_lattice<2>(LatticeType::Square, 7, {.support_radius = 3.5}),
                                                     Kernel<2>(KernelType::WendlandC2), 1.5, 3.4),
                                "square 7 Wendland C2 h 1.5 radius 3.4")});
  std::cout << "2D: ByOffset against PerPair, largest relative difference " << worst << "\n";
}

TEST(MatrixFreeStorage, ByOffsetAgreesWithPerPairIn3D) {
  const double worst = worst_storage_difference(*lattice<3>(5, KernelType::CubicSpline, 1.3), "cubic 5 h 1.3");
  std::cout << "3D: ByOffset against PerPair, largest relative difference " << worst << "\n";
}

TEST(MatrixFreeStorage, AutoFallsBackToPerPairOffAPerfectLattice) {
  Kernel<2> k(KernelType::CubicSpline);
  auto jittered = make_lattice<2>(LatticeType::Square, 8, {.support_radius = 2.6, .perturbation = 0.1, .seed = 3});
  struct Case {
    std::string name;
    std::shared_ptr<const Discretisation<2>> disc;
    std::string reason;  // a word of lattice_refusal()
  };
  const std::vector<Case> cases = {
      {"jittered", make_discretisation(jittered, k, 1.3), "off"},
      {"periodic", lattice<2>(8, KernelType::CubicSpline, 1.3, {.periodic = true}), "periodic"},
      {"free surface", lattice<2>(8, KernelType::CubicSpline, 1.3, {.fixed_layers = 0}), "neighbour set"},
      {"hexagonal", make_discretisation(make_lattice<2>(LatticeType::Hexagonal, 8, {.support_radius = 2.6}), k, 1.3),
       "off its site"}};
  for (const Case& c : cases) {
    const std::string why = MatrixFreeLinearisation<2>::lattice_refusal(*c.disc);
    EXPECT_NE(why.find(c.reason), std::string::npos) << c.name << ": " << why;
    const MatrixFreeLinearisation<2> automatic(*c.disc, kMaterial, MomentumForm::Conservative,
                                               PreStrainKind::Isotropic);
    EXPECT_EQ(automatic.storage(), MatrixFreeStorage::PerPair) << c.name;
    EXPECT_EQ(MatrixFreeLinearisation<2>::estimated_bytes(*c.disc),
              MatrixFreeLinearisation<2>::estimated_bytes(*c.disc, MatrixFreeStorage::PerPair))
        << c.name;
    try {
      MatrixFreeLinearisation<2>(*c.disc, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic,
                                 MatrixFreeStorage::ByOffset);
      ADD_FAILURE() << c.name << ": ByOffset accepted";
    } catch (const std::invalid_argument& e) {
      const std::string m = e.what();
      EXPECT_EQ(m, "MatrixFreeLinearisation: by-offset storage needs a perfect lattice: " + why) << c.name;
      EXPECT_EQ(m.find('\n'), std::string::npos) << c.name;
    }
  }
  EXPECT_TRUE(MatrixFreeLinearisation<2>::lattice_refusal(*lattice<2>(8, KernelType::CubicSpline, 1.3)).empty());
  EXPECT_EQ(parse_matrix_free_storage("by-offset"), MatrixFreeStorage::ByOffset);
  EXPECT_EQ(matrix_free_storage_name(MatrixFreeStorage::PerPair), "per-pair");
  EXPECT_THROW(parse_matrix_free_storage("stencil"), std::invalid_argument);
}

TEST(MatrixFreeStorage, ByOffsetMemoryIsItsEstimateAndFarBelowPerPair) {
  const auto d2 = lattice<2>(40, KernelType::CubicSpline, 1.3);
  const auto d3 = lattice<3>(12, KernelType::CubicSpline, 1.3);
  const MatrixFreeLinearisation<2> l2(*d2, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
  const MatrixFreeLinearisation<3> l3(*d3, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
  ASSERT_EQ(l2.storage(), MatrixFreeStorage::ByOffset);
  ASSERT_EQ(l3.storage(), MatrixFreeStorage::ByOffset);
  const double e2 = MatrixFreeLinearisation<2>::estimated_bytes(*d2);
  const double e3 = MatrixFreeLinearisation<3>::estimated_bytes(*d3);
  EXPECT_GE(l2.memory_bytes(), e2);
  EXPECT_LE(l2.memory_bytes(), 1.05 * e2);
  EXPECT_GE(l3.memory_bytes(), e3);
  EXPECT_LE(l3.memory_bytes(), 1.05 * e3);
  // Per free particle: 2D 4 + 16 bytes and 5 grid values on 48^2 / 40^2 sites against ~21 pairs of G and H;
  // 3D 4 + 24 bytes and 9 values on 20^3 / 12^3 sites against ~81 pairs.
  const double p2 = MatrixFreeLinearisation<2>::estimated_bytes(*d2, MatrixFreeStorage::PerPair);
  const double p3 = MatrixFreeLinearisation<3>::estimated_bytes(*d3, MatrixFreeStorage::PerPair);
  EXPECT_LT(8 * e2, p2) << e2 << " vs " << p2;
  EXPECT_LT(15 * e3, p3) << e3 << " vs " << p3;
}

TEST(MatrixFreeStorage, ThreadCountDoesNotChangeTheBits) {
  if (!threads_available()) GTEST_SKIP() << "built without OpenMP";
  const auto run = [](const auto& lin, int threads) {
    ThreadCountGuard guard(threads);
    const Eigen::VectorXd x = random_vector(lin.dofs(), 5);
    Eigen::VectorXd y(lin.dofs());
    lin.apply(0.7, x, y);
    return y;
  };
  const MatrixFreeLinearisation<2> l2(*lattice<2>(40, KernelType::CubicSpline, 1.3), kMaterial,
                                      MomentumForm::Conservative, PreStrainKind::UniaxialX);
  const MatrixFreeLinearisation<3> l3(*lattice<3>(12, KernelType::CubicSpline, 1.3), kMaterial, MomentumForm::Plus,
                                      PreStrainKind::Isotropic);
  const Eigen::VectorXd a2 = run(l2, 1), b2 = run(l2, 2), a3 = run(l3, 1), b3 = run(l3, 2);
  EXPECT_EQ((a2 - b2).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((a3 - b3).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_GT(a2.cwiseAbs().maxCoeff(), 0.0);
}

/// The critical strain by the preconditioned block LOBPCG from both storages (stencil probed on an 11^Dim lattice
/// when n < 11, as lattice_lobpcg_benchmark).
template <int Dim>
void expect_same_critical_strain(int n) {
  const auto d = lattice<Dim>(n, KernelType::CubicSpline, 1.3);
  const MatrixFreeLinearisation<Dim> pair(*d, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic,
                                          MatrixFreeStorage::PerPair);
  const MatrixFreeLinearisation<Dim> offset(*d, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic,
                                            MatrixFreeStorage::ByOffset);
  const LatticeStencil<Dim> st =
      n >= 11
          ? probe_lattice_stencil(pair, LoadDirection::Tension)
          : probe_lattice_stencil(MatrixFreeLinearisation<Dim>(*lattice<Dim>(11, KernelType::CubicSpline, 1.3),
                                                               kMaterial, MomentumForm::Conservative,
                                                               PreStrainKind::Isotropic, MatrixFreeStorage::PerPair),
                                  LoadDirection::Tension);
  const LatticeSinePreconditioner<Dim> t(st, n);
  const MatrixFreeCriticalLoadOptions o{.method = MatrixFreeEigenMethod::BlockLobpcg, .residual_tol = 1e-10};
  const MatrixFreeCriticalLoad a = matrix_free_critical_load(pair, LoadDirection::Tension, o, t);
  const MatrixFreeCriticalLoad b = matrix_free_critical_load(offset, LoadDirection::Tension, o, t);
  ASSERT_EQ(a.status, Status::Successful) << a.reason;
  ASSERT_EQ(b.status, Status::Successful) << b.reason;
  EXPECT_NEAR(b.load, a.load, 1e-10 * a.load);
  std::cout << Dim << "D n = " << n << ": e_crit per pair " << a.load << ", by offset " << b.load
            << " (relative difference " << std::abs(b.load - a.load) / a.load << ")\n";
}

TEST(MatrixFreeStorage, SameCriticalStrainFromBothStorages) {
  expect_same_critical_strain<2>(24);
  expect_same_critical_strain<3>(10);
}

/// apply_A0_and_A1 (the stiffness and load products of one vector in one call, as the block LOBPCG of
/// matrix_free_critical_load takes them) against its two separate calls: the same bits, every form, one thread or two.
template <int Dim>
void expect_fused_products_same_bits(const Discretisation<Dim>& d, MatrixFreeStorage storage) {
  for (MomentumForm form : all_momentum_forms())
    for (PreStrainKind kind : {PreStrainKind::Isotropic, PreStrainKind::UniaxialX}) {
      const std::string what = momentum_form_name(form) + " " + prestrain_kind_name(kind);
      const MatrixFreeLinearisation<Dim> lin(d, kMaterial, form, kind, storage);
      ASSERT_EQ(lin.storage(), storage);
      const Eigen::VectorXd x = random_vector(lin.dofs(), 11);
      for (double c1 : {-1.0, 0.5, 0.0}) {
        Eigen::VectorXd k(lin.dofs()), l(lin.dofs()), k_ref(lin.dofs()), l_ref(lin.dofs());
        lin.apply_A0(x, k_ref);
        lin.apply_combination(0.0, c1, x, l_ref);
        for (int threads : {1, 2}) {
          set_threads(threads);
          k.setConstant(7.0);
          l.setConstant(7.0);
          lin.apply_A0_and_A1(c1, x, k, l);
          // Bitwise, signed zeros included (== would take -0 for +0).
          EXPECT_EQ(std::memcmp(k.data(), k_ref.data(), sizeof(double) * k.size()), 0) << what << " c1 " << c1;
          EXPECT_EQ(std::memcmp(l.data(), l_ref.data(), sizeof(double) * l.size()), 0) << what << " c1 " << c1;
        }
        set_threads(1);
      }
    }
}

TEST(MatrixFreeStorage, FusedProductsSameBitsAsTwoCalls) {
  const auto d2 = lattice<2>(14, KernelType::CubicSpline, 1.3);
  const auto d3 = lattice<3>(7, KernelType::CubicSpline, 1.3);
  for (MatrixFreeStorage storage : {MatrixFreeStorage::ByOffset, MatrixFreeStorage::PerPair}) {
    expect_fused_products_same_bits(*d2, storage);
    expect_fused_products_same_bits(*d3, storage);
  }
  const MatrixFreeLinearisation<2> lin(*d2, kMaterial, MomentumForm::Conservative, PreStrainKind::UniaxialX);
  Eigen::VectorXd x = Eigen::VectorXd::Ones(lin.dofs()), y(lin.dofs()), z(lin.dofs()), small(3);
  EXPECT_THROW(lin.apply_A0_and_A1(1.0, x, x, z), std::invalid_argument);
  EXPECT_THROW(lin.apply_A0_and_A1(1.0, x, y, y), std::invalid_argument);
  EXPECT_THROW(lin.apply_A0_and_A1(1.0, x, small, z), std::invalid_argument);
  EXPECT_NO_THROW(lin.apply_A0_and_A1(1.0, x, y, z));
}

/// ByOffset's sweeps in their AVX2 build against the baseline build (core/simd_dispatch.hpp): the same bits for every
/// form, both pre-strain kinds and each product, signed zeros included.
template <int Dim>
void expect_avx2_same_bits(const Discretisation<Dim>& d) {
  for (MomentumForm form : all_momentum_forms())
    for (PreStrainKind kind : {PreStrainKind::Isotropic, PreStrainKind::UniaxialX}) {
      const std::string what = momentum_form_name(form) + " " + prestrain_kind_name(kind);
      const MatrixFreeLinearisation<Dim> lin(d, kMaterial, form, kind, MatrixFreeStorage::ByOffset);
      const Eigen::VectorXd x = random_vector(lin.dofs(), 23);
      const auto products = [&] {
        std::vector<Eigen::VectorXd> out(4, Eigen::VectorXd(lin.dofs()));
        lin.apply_A0(x, out[0]);
        lin.apply_A1(x, out[1]);
        lin.apply(-0.3, x, out[2]);
        Eigen::VectorXd l(lin.dofs());
        lin.apply_A0_and_A1(0.5, x, out[3], l);
        out.push_back(l);
        return out;
      };
      const std::vector<Eigen::VectorXd> fast = products();
      const PortableSimdGuard baseline;
      ASSERT_FALSE(avx2_enabled());
      const std::vector<Eigen::VectorXd> base = products();
      for (std::size_t k = 0; k < base.size(); ++k) {
        EXPECT_EQ(std::memcmp(fast[k].data(), base[k].data(), sizeof(double) * base[k].size()), 0)
            << what << " product " << k;
        const bool a1_only = k == 1 || k == 4;  // the minus form's A1 is zero
        if (!a1_only || form != MomentumForm::Minus) EXPECT_GT(base[k].cwiseAbs().maxCoeff(), 0.0) << what << " " << k;
      }
    }
}

TEST(MatrixFreeStorage, Avx2SweepsSameBitsAsBaseline) {
  if (!avx2_enabled()) GTEST_SKIP() << "no AVX2 on this CPU (or SPHSTAB_SIMD=baseline): only the baseline build runs";
  // Lines longer than the sweeps' 128-site chunks, so that full vectors, chunk ends and remainders all occur.
  expect_avx2_same_bits(*lattice<2>(150, KernelType::CubicSpline, 1.3));
  expect_avx2_same_bits(*lattice<3>(9, KernelType::QuinticSpline, 1.2));
}

}  // namespace matrix_free_storage_test
}  // namespace sphstab

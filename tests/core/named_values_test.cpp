#include "sphstab/core/named_values.hpp"

#include <gtest/gtest.h>

#include <initializer_list>
#include <stdexcept>
#include <string>
#include <vector>

#include "sphstab/core/load_direction.hpp"
#include "sphstab/forms/elasticity_2d.hpp"
#include "sphstab/forms/momentum_form.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/forms/stabilised_sph.hpp"
#include "sphstab/forms/wave_1d.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/operators/correction.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/problems/powell_impact.hpp"
#include "sphstab/stability/critical_load.hpp"
#include "sphstab/stability/critical_load_problem.hpp"

namespace sphstab {
namespace named_values_test {

enum class Shape { Square, Hex, Cube };
constexpr NamedValue<Shape> kShapes[] = {
    {Shape::Square, "square"}, {Shape::Hex, "hex"}, {Shape::Hex, "hexagonal"}, {Shape::Cube, "cube"}};

std::string error_of(const std::string& name) {
  try {
    parse_named(name, kShapes, "shape");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

TEST(NamedValues, CanonicalNamesAliasesAndOrder) {
  EXPECT_EQ(name_of(Shape::Hex, kShapes), "hex");  // the first entry of a value, not its alias
  EXPECT_EQ(parse_named("hexagonal", kShapes, "shape"), Shape::Hex);
  EXPECT_EQ(parse_named("cube", kShapes, "shape"), Shape::Cube);
  EXPECT_EQ(valid_names(kShapes), "square, hex, cube");
  EXPECT_EQ(values_of(kShapes), (std::vector<Shape>{Shape::Square, Shape::Hex, Shape::Cube}));
  EXPECT_EQ(name_of(static_cast<Shape>(7), kShapes), "?");
}

TEST(NamedValues, UnknownNameIsOneLineListingTheCanonicalNames) {
  EXPECT_EQ(error_of("tri"), "unknown shape 'tri' (valid: square, hex, cube)");
  EXPECT_EQ(error_of(""), "unknown shape '' (valid: square, hex, cube)");
  EXPECT_EQ(error_of("Hex"), "unknown shape 'Hex' (valid: square, hex, cube)");  // names are case-sensitive
}

// The library's tables: every canonical name parses back to its value, and the documented aliases are accepted.
template <class E, class Parse, class Name>
void expect_round_trip(std::initializer_list<E> values, Parse parse, Name name) {
  for (E v : values) EXPECT_EQ(parse(name(v)), v) << name(v);
}

TEST(NamedValues, LibraryNamesRoundTrip) {
  for (KernelType k : all_kernel_types()) EXPECT_EQ(parse_kernel_type(kernel_name(k)), k);
  for (Correction c : all_corrections()) EXPECT_EQ(parse_correction(correction_name(c)), c);
  for (MomentumForm f : all_momentum_forms()) EXPECT_EQ(parse_momentum_form(momentum_form_name(f)), f);
  expect_round_trip(
      {LatticeType::Line, LatticeType::Square, LatticeType::Hexagonal, LatticeType::FaceCentred, LatticeType::Cubic},
      parse_lattice_type, lattice_name);
  expect_round_trip({CriticalLoadRoute::Auto, CriticalLoadRoute::Assembled, CriticalLoadRoute::MatrixFree,
                     CriticalLoadRoute::Symbol, CriticalLoadRoute::Distributed},
                    parse_critical_load_route, critical_load_route_name);
  expect_round_trip({Criterion::Auto, Criterion::Definiteness, Criterion::Spectrum, Criterion::SymmetricPart},
                    parse_criterion, criterion_name);
  expect_round_trip({CriticalLoadMethod::Eigen, CriticalLoadMethod::Bisection, CriticalLoadMethod::Both},
                    parse_critical_load_method, critical_load_method_name);
  expect_round_trip({LoadDirection::Tension, LoadDirection::Compression}, parse_load_direction, load_direction_name);
  expect_round_trip({PreStrainKind::Isotropic, PreStrainKind::UniaxialX}, parse_prestrain_kind, prestrain_kind_name);
  expect_round_trip({SwitchRule::Tension, SwitchRule::AsPrinted, SwitchRule::Always, SwitchRule::Never},
                    parse_switch_rule, switch_rule_name);
  expect_round_trip(
      {CorrectedOperator::Auto, CorrectedOperator::Divergence, CorrectedOperator::Strain, CorrectedOperator::Both},
      parse_corrected_operator, corrected_operator_name);
  expect_round_trip({ImpactProblem::Symmetric, ImpactProblem::Bar, ImpactProblem::Beam}, parse_impact_problem,
                    impact_problem_name);
  // Aliases: parsed, never printed.
  EXPECT_EQ(parse_lattice_type("fcc"), LatticeType::FaceCentred);
  EXPECT_EQ(lattice_name(parse_lattice_type("hexagonal")), "hex");
  EXPECT_EQ(critical_load_route_name(parse_critical_load_route("petsc")), "distributed");
  EXPECT_EQ(parse_criterion("pd"), Criterion::Definiteness);
  EXPECT_EQ(parse_prestrain_kind("uniaxial-x"), PreStrainKind::UniaxialX);
  EXPECT_THROW(parse_pair_loop("row"), std::invalid_argument);
}

}  // namespace named_values_test
}  // namespace sphstab

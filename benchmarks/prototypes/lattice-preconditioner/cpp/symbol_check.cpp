// Prints the toolkit's ElasticSymbol2D a0(k), -a1(k) (square, cubic, h = 1.3, rho = 1, conservative, isotropic),
// to compare with the symbol of the stencil extracted from the exported matrices (symbol_compare.py).
#include <cstdio>
#include "sphstab/spectral/fourier_symbol_2d.hpp"
using namespace sphstab;
int main() {
  const ElasticMaterial m = ElasticMaterial::from_lame(1.2115384615384615, 0.80769230769230769, 1.0);
  ElasticSymbol2D sym(LatticeType::Square, Kernel<2>(KernelType::CubicSpline), 1.3, 1.0, m, MomentumForm::Conservative,
                      PreStrainKind::Isotropic);
  const double k[][2] = {{0.3, 0.7}, {1.5707963267948966, 0.0}, {3.0, 0.4}, {3.141592653589793, 1.5707963267948966}, {2.9, 2.2}};
  for (auto& kk : k) {
    auto v = sym(Eigen::Vector2d(kk[0], kk[1]));
    std::printf("%.17g %.17g  %.17g %.17g %.17g %.17g  %.17g %.17g %.17g %.17g\n", kk[0], kk[1], v.a0(0, 0), v.a0(0, 1),
                v.a0(1, 0), v.a0(1, 1), -v.a1(0, 0), -v.a1(0, 1), -v.a1(1, 0), -v.a1(1, 1));
  }
}

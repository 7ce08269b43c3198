#pragma once
/// \file quadrature.hpp
/// Composite Gauss-Legendre quadrature (16 nodes per panel) for smooth or piecewise-smooth integrands.
#include <functional>

namespace sphstab {

/// Integral of f over [a, b] using `panels` equal panels of 16-point Gauss-Legendre; exact for polynomials
/// of degree <= 31 on each panel, so piecewise polynomials are exact when their breaks fall on panel edges.
double integrate_gauss_legendre(const std::function<double(double)>& f, double a, double b, int panels);

}  // namespace sphstab

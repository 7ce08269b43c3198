#pragma once
/// \file scratch.hpp
/// An evaluator's scratch arrays for its real and its complex overloads (the complex ones serve complex-step
/// Jacobians), kept between calls so that a step does not allocate.
#include <complex>
#include <type_traits>

namespace sphstab {

/// Holds Work<double> and Work<std::complex<double>>. Copying the owner does not copy them: the copy starts empty, so
/// a copied form neither shares nor duplicates another's buffers (every entry an evaluation reads is written earlier in
/// the same call).
template <template <class> class Work>
class Scratch {
 public:
  Scratch() = default;
  Scratch(const Scratch&) {}
  Scratch(Scratch&&) = default;
  Scratch& operator=(const Scratch&) { return *this; }
  Scratch& operator=(Scratch&&) = default;

  template <class Scalar>
  Work<Scalar>& get() {
    if constexpr (std::is_same_v<Scalar, double>)
      return m_real;
    else
      return m_complex;
  }

 private:
  Work<double> m_real;
  Work<std::complex<double>> m_complex;
};

}  // namespace sphstab

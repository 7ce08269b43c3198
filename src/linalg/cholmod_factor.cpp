#include "sphstab/linalg/cholmod_factor.hpp"

#include <Eigen/CholmodSupport>
#include <stdexcept>
#include <string>

#include "sphstab/core/format.hpp"
#include "sphstab/core/memory_budget.hpp"

namespace sphstab {

namespace detail {

/// Eigen's CholmodDecomposition with its protected factor exposed for the partial solves.
class ExposedCholmod : public Eigen::CholmodDecomposition<ColSparseMatrix, Eigen::Lower> {
 public:
  cholmod_factor* factor() const { return m_cholmodFactor; }
};

}  // namespace detail

struct CholmodFactor::Impl {
  detail::ExposedCholmod chol;
  mutable cholmod_dense* x = nullptr;  // cholmod_solve2 workspaces, reused across solves
  mutable cholmod_dense* y = nullptr;
  mutable cholmod_dense* e = nullptr;
  bool analysed = false;
  bool factorised = false;

  ~Impl() {
    cholmod_common& c = chol.cholmod();
    if (x) cholmod_free_dense(&x, &c);
    if (y) cholmod_free_dense(&y, &c);
    if (e) cholmod_free_dense(&e, &c);
  }
};

CholmodFactor::CholmodFactor(CholmodVariant variant, CholmodFactorKind kind)
    : m_impl(std::make_unique<Impl>()), m_variant(variant), m_kind(kind) {
  auto& chol = m_impl->chol;
  chol.cholmod().print = 0;  // silence "CHOLMOD warning: not positive definite"; failures go through info()
  chol.cholmod().error_handler = nullptr;
  if (kind == CholmodFactorKind::LDLT) {
    chol.setMode(Eigen::CholmodLDLt);
  } else {
    chol.setMode(variant == CholmodVariant::Supernodal ? Eigen::CholmodSupernodalLLt : Eigen::CholmodSimplicialLLt);
  }
}

CholmodFactor::~CholmodFactor() = default;
CholmodFactor::CholmodFactor(CholmodFactor&&) noexcept = default;
CholmodFactor& CholmodFactor::operator=(CholmodFactor&&) noexcept = default;

void CholmodFactor::analyze_pattern(const ColSparseMatrix& lower) {
  if (lower.rows() != lower.cols() || lower.rows() == 0)
    throw std::invalid_argument("CholmodFactor::analyze_pattern: matrix must be square and non-empty (got " +
                                std::to_string(lower.rows()) + " x " + std::to_string(lower.cols()) + ")");
  if (!lower.isCompressed())
    throw std::invalid_argument("CholmodFactor::analyze_pattern: matrix must be compressed (call makeCompressed())");
  m_impl->chol.analyzePattern(lower);
  // The analysis knows the factor's fill for the chosen ordering (Common->lnz): check it before factorising.
  // 12 bytes per entry (value + row index), 1.5x for supernodal padding and workspace.
  const double lnz = m_impl->chol.cholmod().lnz;
  require_memory(1.5 * 12.0 * lnz, "Cholesky factor (CHOLMOD, n = " + std::to_string(lower.rows()) + ", " +
                                       format_number(lnz, 3) + " nonzeros in L)");
  m_impl->analysed = true;
  m_impl->factorised = false;
  m_n = lower.rows();
  m_info = Status::NotComputed;
}

bool CholmodFactor::factorize(const ColSparseMatrix& lower) {
  if (!m_impl->analysed) throw std::logic_error("CholmodFactor::factorize: call analyze_pattern() first");
  if (lower.rows() != m_n || lower.cols() != m_n)
    throw std::invalid_argument("CholmodFactor::factorize: size differs from the analysed pattern");
  m_impl->chol.factorize(lower);
  const bool ok = m_impl->chol.info() == Eigen::Success;
  m_impl->factorised = ok;
  m_info = ok ? Status::Successful : Status::NumericalIssue;
  return ok;
}

bool CholmodFactor::compute(const ColSparseMatrix& lower) {
  analyze_pattern(lower);
  return factorize(lower);
}

int CholmodFactor::failed_column() const {
  const cholmod_factor* f = m_impl->chol.factor();
  return f ? static_cast<int>(f->minor) : 0;
}

double CholmodFactor::rcond_estimate() const {
  if (!m_impl->factorised) return 0.0;
  return cholmod_rcond(m_impl->chol.factor(), &m_impl->chol.cholmod());
}

void CholmodFactor::solve(CholmodSystem sys, const double* x, double* y) const {
  if (!m_impl->factorised) throw std::logic_error("CholmodFactor::solve: no successful factorisation");
  // CholmodSystem's order: A, L, Lt, P, Pt.
  constexpr int kCodes[] = {CHOLMOD_A, CHOLMOD_L, CHOLMOD_Lt, CHOLMOD_P, CHOLMOD_Pt};
  const int code = kCodes[static_cast<int>(sys)];
  cholmod_dense b;
  b.nrow = static_cast<size_t>(m_n);
  b.ncol = 1;
  b.nzmax = static_cast<size_t>(m_n);
  b.d = static_cast<size_t>(m_n);
  b.x = const_cast<double*>(x);
  b.z = nullptr;
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  cholmod_common& c = m_impl->chol.cholmod();
  if (!cholmod_solve2(code, m_impl->chol.factor(), &b, nullptr, &m_impl->x, nullptr, &m_impl->y, &m_impl->e, &c))
    throw std::runtime_error("CholmodFactor::solve: cholmod_solve2 failed (status " + std::to_string(c.status) + ")");
  const double* out = static_cast<const double*>(m_impl->x->x);
  std::copy(out, out + m_n, y);
}

}  // namespace sphstab

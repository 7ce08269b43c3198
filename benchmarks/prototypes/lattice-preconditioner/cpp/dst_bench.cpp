// Cost of the preconditioner's transforms: one T application = 2 components x (forward + inverse) 2D DST-I of an
// n x n field. (a) FFTW r2r RODFT00 (2D plan, FFTW_MEASURE), (b) Eigen's unsupported FFT (kissfft backend) with the
// DST-I written as a real FFT of the odd extension of length 2(n+1), row by row then column by column.
#include <fftw3.h>
#include <unsupported/Eigen/FFT>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <vector>

using clk = std::chrono::steady_clock;

// 1D DST-I (unnormalised, FFTW's RODFT00 convention: Y_k = 2 sum_j x_j sin(pi (j+1)(k+1)/(n+1))) via a real FFT.
struct EigenDst {
  int n; Eigen::FFT<double> fft; std::vector<double> ext; std::vector<std::complex<double>> spec;
  explicit EigenDst(int n_) : n(n_), ext(2 * (n_ + 1)), spec(2 * (n_ + 1)) {}
  void operator()(const double* x, int stride, double* y, int ystride) {
    const int m = 2 * (n + 1);
    ext[0] = 0; ext[n + 1] = 0;
    for (int j = 0; j < n; ++j) { ext[j + 1] = x[j * stride]; ext[m - 1 - j] = -x[j * stride]; }
    fft.fwd(spec, ext);
    for (int k = 0; k < n; ++k) y[k * ystride] = -spec[k + 1].imag();
  }
};

int main(int argc, char** argv) {
  for (int ai = 1; ai < argc; ++ai) {
    const int n = std::atoi(argv[ai]);
    std::vector<double> a(n * n), b(n * n), c(n * n);
    for (int i = 0; i < n * n; ++i) a[i] = std::sin(0.1 * i) + 0.01 * (i % 7);
    // FFTW
    auto t0 = clk::now();
    fftw_plan p = fftw_plan_r2r_2d(n, n, a.data(), b.data(), FFTW_RODFT00, FFTW_RODFT00, FFTW_MEASURE);
    double plan_s = std::chrono::duration<double>(clk::now() - t0).count();
    for (int i = 0; i < n * n; ++i) a[i] = std::sin(0.1 * i) + 0.01 * (i % 7);
    const int reps = n <= 512 ? 20 : 5;
    t0 = clk::now();
    for (int r = 0; r < reps; ++r) fftw_execute(p);
    double fftw_s = std::chrono::duration<double>(clk::now() - t0).count() / reps;
    // Eigen / kissfft
    EigenDst d(n);
    t0 = clk::now();
    for (int r = 0; r < reps; ++r) {
      for (int i = 0; i < n; ++i) d(&a[i * n], 1, &c[i * n], 1);   // rows
      for (int j = 0; j < n; ++j) d(&c[j], n, &c[j], n);           // columns (in place is fine: ext copies)
    }
    double eig_s = std::chrono::duration<double>(clk::now() - t0).count() / reps;
    double err = 0, mx = 0;
    for (int i = 0; i < n * n; ++i) { err = std::fmax(err, std::fabs(b[i] - c[i])); mx = std::fmax(mx, std::fabs(b[i])); }
    // one T application = 4 such 2D transforms (2 components x forward + inverse)
    std::printf("n=%d: 2D DST-I  FFTW %.3f ms (plan %.2f s)  Eigen/kissfft %.3f ms  | per T apply: FFTW %.2f ms, Eigen %.2f ms"
                "  | max diff %.1e (rel %.1e)\n", n, 1e3 * fftw_s, plan_s, 1e3 * eig_s, 4e3 * fftw_s, 4e3 * eig_s, err, err / mx);
    fftw_destroy_plan(p);
  }
}

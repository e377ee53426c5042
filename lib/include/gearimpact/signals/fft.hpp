// The discrete Fourier transforms the signal layer uses, behind one interface
// so that the FFT library (FFTW3) appears in one source file only.
#pragma once

#include <complex>
#include <cstddef>
#include <vector>

namespace gearimpact::signals {

// X_k = sum_n x_n exp(-2 pi i k n / N) for k = 0..N/2 (the other half is the
// conjugate mirror of a real signal). Unnormalised. N >= 1.
std::vector<std::complex<double>> real_dft(const std::vector<double>& x);

// The real signal of `n` samples whose real_dft is `half` (n/2 + 1 values):
// x_n = (1/N) sum_k X_k exp(+2 pi i k n / N), the mirror half implied.
std::vector<double> inverse_real_dft(const std::vector<std::complex<double>>& half, std::size_t n);

// z_n = (1/N) sum_k Z_k exp(+2 pi i k n / N) of a complex spectrum of N values.
std::vector<std::complex<double>> inverse_dft(const std::vector<std::complex<double>>& spectrum);

}  // namespace gearimpact::signals

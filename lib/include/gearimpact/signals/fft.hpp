// The discrete Fourier transforms the signal layer uses, behind one interface
// so that the FFT library (FFTW3) appears in one source file only.
#pragma once

#include <complex>
#include <cstddef>
#include <vector>

namespace gearimpact::signals {

// Throws InputError naming `name` unless every |x_n| is at most 1e300 / N, so that no sum of a
// transform of x overflows a double (each |X_k| is at most N max |x_n|): 8 samples of 1e308 once
// came out as inf and NaN. The values must be finite (checked by the callers).
void check_dft_range(const std::vector<double>& x, const char* name);

// X_k = sum_n x_n exp(-2 pi i k n / N) for k = 0..N/2 (the other half is the
// conjugate mirror of a real signal). Unnormalised. N >= 1.
std::vector<std::complex<double>> real_dft(const std::vector<double>& x);

// The real signal of `n` samples whose real_dft is `half` (n/2 + 1 values):
// x_n = (1/N) sum_k X_k exp(+2 pi i k n / N), the mirror half implied.
std::vector<double> inverse_real_dft(const std::vector<std::complex<double>>& half, std::size_t n);

// z_n = (1/N) sum_k Z_k exp(+2 pi i k n / N) of a complex spectrum of N values.
std::vector<std::complex<double>> inverse_dft(const std::vector<std::complex<double>>& spectrum);

}  // namespace gearimpact::signals

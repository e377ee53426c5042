// The single-sided amplitude spectrum of a real, uniformly sampled signal.
#pragma once

#include <string_view>
#include <vector>

namespace gearimpact::signals {

// The window applied before the transform. Hann is the periodic (DFT-even)
// form w_n = (1 - cos(2 pi n / N)) / 2, n = 0..N-1, whose coherent gain
// (the mean of w) is exactly 1/2.
enum class Window { rectangular, hann };

std::string_view to_string(Window window);
// "rectangular" or "hann"; throws InputError naming `field` otherwise.
Window parse_window(std::string_view text, std::string_view field);

struct Spectrum {
  // Bin k at k * rate / N, k = 0..N/2: Hz for a time signal, orders (cycles
  // per revolution) for a signal sampled in angle with rate = samples per revolution.
  std::vector<double> frequency;
  // Amplitude scaling: a sinusoid of amplitude A exactly at a bin reads A,
  // whatever the window: A_k = 2 |X_k| / sum(w) for 0 < k < N/2, and
  // |X_k| / sum(w) at k = 0 (the mean) and at k = N/2 for even N.
  // Between bins a sinusoid reads less (the scalloping loss): with the
  // rectangular window sin(pi d) / (pi d) of A at a distance of d bins, with
  // Hann sin(pi d) / (pi d (1 - d^2)), i.e. 0.637 A and 0.849 A at d = 1/2.
  std::vector<double> amplitude;
  Window window = Window::rectangular;
  double resolution = 0.0;     // rate / N
  double coherent_gain = 1.0;  // sum(w) / N: 1 rectangular, 1/2 Hann
};

// Throws InputError for fewer than 2 samples, a non-finite sample or a rate
// that is not finite and > 0.
Spectrum amplitude_spectrum(const std::vector<double>& signal, double rate,
                            Window window = Window::hann);

}  // namespace gearimpact::signals

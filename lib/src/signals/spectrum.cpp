#include "gearimpact/signals/spectrum.hpp"

#include <cmath>
#include <complex>
#include <string>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/signals/fft.hpp"
#include "gearimpact/signals/resample.hpp"

namespace gearimpact::signals {

std::string_view to_string(Window window) {
  return window == Window::hann ? "hann" : "rectangular";
}

Window parse_window(std::string_view text, std::string_view field) {
  if (text == "hann") return Window::hann;
  if (text == "rectangular") return Window::rectangular;
  throw InputError(std::string(field), std::string(text), "rectangular or hann");
}

Spectrum amplitude_spectrum(const std::vector<double>& signal, double rate, Window window) {
  check_sample_rate(rate);
  const std::size_t n = signal.size();
  if (n < 2) {
    throw InputError("signal length", std::to_string(n), "at least 2 samples");
  }
  std::vector<double> weighted(n);
  double weight_sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(signal[i])) {
      throw InputError("signal sample " + std::to_string(i), signal[i], "a finite value");
    }
    const double w =
        window == Window::hann
            ? 0.5 * (1.0 - std::cos(2.0 * pi * static_cast<double>(i) / static_cast<double>(n)))
            : 1.0;
    weight_sum += w;
    weighted[i] = w * signal[i];
  }
  check_dft_range(signal, "signal");
  const std::vector<std::complex<double>> x = real_dft(weighted);
  Spectrum s;
  s.window = window;
  s.resolution = rate / static_cast<double>(n);
  s.coherent_gain = weight_sum / static_cast<double>(n);
  s.frequency.resize(x.size());
  s.amplitude.resize(x.size());
  for (std::size_t k = 0; k < x.size(); ++k) {
    s.frequency[k] = static_cast<double>(k) * s.resolution;
    // A sinusoid's energy splits between +f and -f except at 0 and at N/2.
    const bool own_mirror = k == 0 || 2 * k == n;
    s.amplitude[k] = (own_mirror ? 1.0 : 2.0) * std::abs(x[k]) / weight_sum;
  }
  return s;
}

}  // namespace gearimpact::signals

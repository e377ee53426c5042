#include "gearimpact/signals/fft.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <mutex>
#include <string>

#include "gearimpact/error.hpp"

namespace gearimpact::signals {
namespace {

// FFTW's planner is not thread-safe (its execution is): plans are made and
// destroyed under one lock. FFTW_ESTIMATE plans without timing trial runs,
// so the result does not depend on the machine's load.
std::mutex& planner_mutex() {
  static std::mutex m;
  return m;
}

struct Plan {
  fftw_plan plan = nullptr;
  ~Plan() {
    if (plan != nullptr) {
      const std::lock_guard lock(planner_mutex());
      fftw_destroy_plan(plan);
    }
  }
};

struct FftwFree {
  void operator()(void* p) const { fftw_free(p); }
};
template <typename T>
using Buffer = std::unique_ptr<T[], FftwFree>;

template <typename T>
Buffer<T> allocate(std::size_t n) {
  auto* p = static_cast<T*>(fftw_malloc(sizeof(T) * (n == 0 ? 1 : n)));
  if (p == nullptr) throw Error("FFT: cannot allocate " + std::to_string(n) + " values");
  return Buffer<T>(p);
}

int checked_size(std::size_t n) {
  if (n == 0 || n > static_cast<std::size_t>(1) << 30) {
    throw Error("FFT: length " + std::to_string(n) + " outside 1..2^30");
  }
  return static_cast<int>(n);
}

}  // namespace

void check_dft_range(const std::vector<double>& x, const char* name) {
  const double largest = 1e300 / static_cast<double>(std::max<std::size_t>(x.size(), 1));
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!(std::fabs(x[i]) <= largest)) {
      throw InputError(std::string(name) + " (sample " + std::to_string(i + 1) + ")", x[i],
                       "a magnitude of at most 1e300 / N = " + format_number(largest) +
                           " for its N = " + std::to_string(x.size()) +
                           " samples: a larger one overflows the transform's sums");
    }
  }
}

std::vector<std::complex<double>> real_dft(const std::vector<double>& x) {
  const int n = checked_size(x.size());
  const std::size_t half = x.size() / 2 + 1;
  Buffer<double> in = allocate<double>(x.size());
  Buffer<fftw_complex> out = allocate<fftw_complex>(half);
  Plan p;
  {
    const std::lock_guard lock(planner_mutex());
    p.plan = fftw_plan_dft_r2c_1d(n, in.get(), out.get(), FFTW_ESTIMATE);
  }
  // Filled after planning: a planner may overwrite its arrays.
  std::memcpy(in.get(), x.data(), sizeof(double) * x.size());
  fftw_execute(p.plan);
  std::vector<std::complex<double>> result(half);
  for (std::size_t k = 0; k < half; ++k) result[k] = {out[k][0], out[k][1]};
  return result;
}

std::vector<double> inverse_real_dft(const std::vector<std::complex<double>>& half, std::size_t n) {
  const int size = checked_size(n);
  if (half.size() != n / 2 + 1) {
    throw Error("inverse FFT: " + std::to_string(half.size()) + " bins for " + std::to_string(n) +
                " samples (needs n/2 + 1)");
  }
  Buffer<fftw_complex> in = allocate<fftw_complex>(half.size());
  Buffer<double> out = allocate<double>(n);
  Plan p;
  {
    const std::lock_guard lock(planner_mutex());
    p.plan = fftw_plan_dft_c2r_1d(size, in.get(), out.get(), FFTW_ESTIMATE);
  }
  for (std::size_t k = 0; k < half.size(); ++k) {
    in[k][0] = half[k].real();
    in[k][1] = half[k].imag();
  }
  fftw_execute(p.plan);  // c2r overwrites its input, which is our copy
  std::vector<double> result(n);
  for (std::size_t i = 0; i < n; ++i) result[i] = out[i] / static_cast<double>(n);
  return result;
}

std::vector<std::complex<double>> inverse_dft(const std::vector<std::complex<double>>& spectrum) {
  const std::size_t n = spectrum.size();
  const int size = checked_size(n);
  Buffer<fftw_complex> in = allocate<fftw_complex>(n);
  Buffer<fftw_complex> out = allocate<fftw_complex>(n);
  Plan p;
  {
    const std::lock_guard lock(planner_mutex());
    p.plan = fftw_plan_dft_1d(size, in.get(), out.get(), FFTW_BACKWARD, FFTW_ESTIMATE);
  }
  for (std::size_t k = 0; k < n; ++k) {
    in[k][0] = spectrum[k].real();
    in[k][1] = spectrum[k].imag();
  }
  fftw_execute(p.plan);
  std::vector<std::complex<double>> result(n);
  const double scale = 1.0 / static_cast<double>(n);
  for (std::size_t i = 0; i < n; ++i) result[i] = {out[i][0] * scale, out[i][1] * scale};
  return result;
}

}  // namespace gearimpact::signals

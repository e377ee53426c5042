// The ring-housing sensor (signals/planet_pass.hpp) against exact properties
// (docs/planetary.md): the default windows of equally spaced planets sum to 1
// (w(phi) + w(phi - D) = 1 for adjacent planets, cos(x) + cos(x - pi) = 0), so
// a constant force reads constant; and the ring-sensor rule on synthetic
// forces: identical, equally spaced planets whose forces are one function of
// time shifted by 1/N of a carrier turn per planet make y periodic in 1/N
// turn, so its spectrum over whole carrier turns holds only multiples of
// N f_c (to rounding); one planet unlike the others breaks it.
#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <optional>
#include <string>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/signals/fft.hpp"
#include "gearimpact/signals/planet_pass.hpp"

using namespace gearimpact;
using namespace gearimpact::signals;

namespace {

std::vector<double> equal_angles(int n) {
  std::vector<double> psi;
  for (int i = 0; i < n; ++i) psi.push_back(2.0 * pi * i / n);
  return psi;
}

// A ring-mesh force of a ring-fixed stage (Z_r = 80: f_m = 80 f_c), as a function of the time
// in carrier turns: a mean, mesh harmonics and a once-a-turn part, all periodic in one turn.
double force(double turns) {
  const double zr = 80.0;
  return 1000.0 + 120.0 * std::cos(2.0 * pi * zr * turns + 0.3) +
         45.0 * std::sin(2.0 * pi * 2.0 * zr * turns - 1.1) +
         30.0 * std::cos(2.0 * pi * turns + 0.7);
}

struct Comb {
  double on = 0.0;   // the largest line at a multiple of N f_c (the mean left out)
  double off = 0.0;  // the largest line elsewhere
};

// y over `turns` whole carrier turns at `samples` a turn, carrier at constant speed; planet n's
// force the same function `turns` ahead by n / N (it is where planet 0 will be) times scale[n].
Comb comb_of(int planets, const std::vector<double>& scale, const std::vector<double>& psi) {
  const int turns = 4;
  // Samples a turn: a multiple of every N here, so that the orders of y above Nyquist (the
  // window's kinks in its second derivative make them fall only as order^-3) alias onto
  // multiples of N too; the forces' highest order, 160, is below Nyquist (480).
  const int samples = 960;
  const std::size_t total = static_cast<std::size_t>(turns * samples);
  std::vector<double> carrier(total);
  std::vector<std::vector<double>> forces(static_cast<std::size_t>(planets),
                                          std::vector<double>(total));
  for (std::size_t i = 0; i < total; ++i) {
    const double t = static_cast<double>(i) / samples;  // carrier turns
    carrier[i] = 2.0 * pi * t;
    for (int n = 0; n < planets; ++n) {
      const auto at = static_cast<std::size_t>(n);
      forces[at][i] = scale[at] * force(t + psi[at] / (2.0 * pi));
    }
  }
  const std::vector<double> y = ring_sensor_signal(forces, carrier, psi, {0.4, std::nullopt});
  const std::vector<std::complex<double>> spectrum = real_dft(y);
  Comb c;
  for (std::size_t k = 1; k < spectrum.size(); ++k) {
    // Bin k is k / turns carrier orders: on the comb where k / turns is a multiple of N.
    const bool on = k % static_cast<std::size_t>(turns * planets) == 0;
    double& line = on ? c.on : c.off;
    line = std::max(line, std::abs(spectrum[k]));
  }
  return c;
}

}  // namespace

TEST_CASE("the default windows of equally spaced planets sum to 1; a constant force reads it") {
  for (int planets : {3, 4, 5, 7}) {
    CAPTURE(planets);
    const std::vector<double> psi = equal_angles(planets);
    const double d = default_planet_pass_half_width(planets);
    CHECK(d == 2.0 * pi / planets);
    std::vector<double> carrier;
    for (int i = 0; i < 2000; ++i) carrier.push_back(-7.0 + 0.01234 * i);
    double worst = 0.0;
    for (double c : carrier) {
      double sum = 0.0;
      for (double p : psi) sum += planet_pass_window(c + p - 1.3, d);
      worst = std::max(worst, std::fabs(sum - 1.0));
    }
    // Two windows overlap at a time, each ~1 with a rounding of a few 1e-16.
    CHECK(worst < 1e-14);
    const std::vector<std::vector<double>> constant(static_cast<std::size_t>(planets),
                                                    std::vector<double>(carrier.size(), 250.0));
    const std::vector<double> y = ring_sensor_signal(constant, carrier, psi, {1.3, std::nullopt});
    for (double v : y) REQUIRE(std::fabs(v - 250.0) < 250.0 * 1e-14);
  }
  // The window's shape: 1 at the sensor, 1/2 at D/2, 0 from D on, wrapped to (-pi, pi].
  CHECK(planet_pass_window(0.0, 1.0) == 1.0);
  CHECK(std::fabs(planet_pass_window(0.5, 1.0) - 0.5) < 1e-15);
  CHECK(planet_pass_window(1.0, 1.0) == 0.0);
  CHECK(std::fabs(planet_pass_window(2.0 * pi + 0.5, 1.0) - 0.5) < 1e-14);
  CHECK(wrap_to_pi(-pi) == pi);
  CHECK(wrap_to_pi(pi) == pi);
  CHECK(std::fabs(wrap_to_pi(3.0 * pi / 2.0) + pi / 2.0) < 1e-15);
}

TEST_CASE("identical equally spaced planets give only multiples of N f_c; one unlike breaks it") {
  for (int planets : {3, 4, 5}) {
    CAPTURE(planets);
    const std::vector<double> psi = equal_angles(planets);
    const Comb alike =
        comb_of(planets, std::vector<double>(static_cast<std::size_t>(planets), 1.0), psi);
    CAPTURE(alike.on);
    CAPTURE(alike.off);
    REQUIRE(alike.on > 1.0);
    // Rounding: the DFT of 3840 samples of ~1e3 N, each off-comb bin ~ sqrt(3840) 1e3 1e-16.
    CHECK(alike.off < 1e-11 * alike.on);
    // One planet with 5 % stiffer meshes (its force 5 % larger): lines at every carrier order.
    std::vector<double> scale(static_cast<std::size_t>(planets), 1.0);
    scale[1] = 1.05;
    const Comb unlike = comb_of(planets, scale, psi);
    CHECK(unlike.off > 1e-3 * unlike.on);
  }
  // Unequal spacing breaks it as well (the windows no longer tile the turn evenly).
  const Comb unequal = comb_of(3, {1.0, 1.0, 1.0}, {0.0, 2.0, 4.3});
  CHECK(unequal.off > 1e-3 * unequal.on);
}

TEST_CASE("the ring sensor refuses bad input by name") {
  const std::vector<double> carrier{0.0, 0.1};
  const std::vector<std::vector<double>> forces{{1.0, 1.0}, {1.0, 1.0}, {1.0, 1.0}};
  const std::vector<double> psi = equal_angles(3);
  const auto message = [&](const std::vector<std::vector<double>>& f, const std::vector<double>& c,
                           const std::vector<double>& p, RingSensor s) {
    try {
      ring_sensor_signal(f, c, p, s);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(taken)");
  };
  CHECK(message(forces, carrier, psi, {0.0, -1.0}).find("half_width") != std::string::npos);
  CHECK(message(forces, carrier, psi, {0.0, 4.0}).find("(0, pi]") != std::string::npos);
  CHECK(message(forces, carrier, psi, {0.0, 0.0}).find("half_width") != std::string::npos);
  CHECK(message({{1.0, 1.0}}, carrier, psi, {}).find("forces") != std::string::npos);
  CHECK(message(forces, {0.0}, psi, {}).find("forces[0]") != std::string::npos);
  CHECK(message(forces, {0.0, std::nan("")}, psi, {}).find("carrier_angle") != std::string::npos);
  CHECK(message(forces, carrier, {}, {}).find("planet_angles") != std::string::npos);
  // A user D in range is taken: pi covers the whole turn.
  CHECK(ring_sensor_signal(forces, carrier, psi, {0.0, pi}).size() == 2);
}

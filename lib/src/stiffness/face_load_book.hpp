// The load across the face of a helical pair's loaded STE, booked angle by
// angle (docs/helical.md, "Loaded STE and the load across the face"): each
// angle's load centre and face-load factor, the mean load per slice over the
// angles, the largest factor, and the STE's mean and peak to peak. Both
// routes of helical_static_transmission_error book through it: the slices'
// (helical_ste.cpp) and a faulted pair's tables (helical_faults.cpp).
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <utility>

#include "gearimpact/stiffness/helical_ste.hpp"

namespace gearimpact {

class FaceLoadBook {
 public:
  // result's force_n, face_width_m and slice_y_m set; `angles` points to come.
  FaceLoadBook(HelicalStaticTransmissionError& result, long long angles)
      : result_(result),
        angles_(angles),
        nominal_(result.force_n / result.face_width_m),
        slices_(result.slice_y_m.size()) {
    result_.points.reserve(static_cast<std::size_t>(angles));
    result_.mean_load_per_width_n_per_m.assign(slices_, 0.0);
  }

  // One angle with its ste_m and load_per_width_n_per_m set: its load centre
  // (mid-face where nothing is carried) and face-load factor, the largest load
  // per unit width over the nominal F_bt / b.
  void add(HelicalStePoint p) {
    double total = 0.0;
    double moment = 0.0;
    double peak = 0.0;
    for (std::size_t j = 0; j < slices_; ++j) {
      const double w = p.load_per_width_n_per_m[j];
      total += w;
      moment += w * result_.slice_y_m[j];
      peak = std::max(peak, w);
      result_.mean_load_per_width_n_per_m[j] += w;
    }
    p.load_centre_m = total > 0.0 ? moment / total : 0.5 * result_.face_width_m;
    p.face_load_factor = peak / nominal_;
    result_.largest_face_load_factor =
        std::max(result_.largest_face_load_factor, p.face_load_factor);
    sum_ += p.ste_m;
    least_ = std::min(least_, p.ste_m);
    most_ = std::max(most_, p.ste_m);
    result_.points.push_back(std::move(p));
  }

  // After the last angle: the mean load across the face, its factor and centre,
  // and the STE's mean and peak to peak.
  void finish() {
    double total = 0.0;
    double moment = 0.0;
    double peak = 0.0;
    for (std::size_t j = 0; j < slices_; ++j) {
      double& w = result_.mean_load_per_width_n_per_m[j];
      w /= static_cast<double>(angles_);
      total += w;
      moment += w * result_.slice_y_m[j];
      peak = std::max(peak, w);
    }
    result_.face_load_factor = peak / nominal_;
    result_.mean_load_centre_m = moment / total;
    result_.ste_mean_m = sum_ / static_cast<double>(angles_);
    result_.ste_peak_to_peak_m = most_ - least_;
  }

 private:
  HelicalStaticTransmissionError& result_;
  long long angles_;
  double nominal_;
  std::size_t slices_;
  double sum_ = 0.0;
  double least_ = std::numeric_limits<double>::infinity();
  double most_ = -std::numeric_limits<double>::infinity();
};

}  // namespace gearimpact

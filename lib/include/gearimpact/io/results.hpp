// The program's tables and summaries as text, one writer each, shared by the
// commands and the reproduction: CSV at 17 significant digits (every double
// reads back exactly), JSON with absent values as null.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "gearimpact/batch/sweep_friction.hpp"
#include "gearimpact/dynamics/planetary_train.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/train.hpp"
#include "gearimpact/io/columns.hpp"
#include "gearimpact/stiffness/energy.hpp"
#include "gearimpact/stiffness/helical.hpp"
#include "gearimpact/stiffness/helical_ste.hpp"
#include "gearimpact/stiffness/iso6336.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "gearimpact/stiffness/mesh_tables.hpp"
#include "gearimpact/stiffness/static_transmission_error.hpp"
#include "gearimpact/stiffness/time_varying_stiffness.hpp"

namespace gearimpact {

// A number of a CSV file or a gnuplot script: 17 significant digits ("%.17g"),
// the form the files have always had, so that their bytes do not change with the
// shorter form of messages (format_number).
std::string format_data_number(double value);

// The time series of a two-gear torsional run (SimulationResult::series), each column described
// once: t_s,theta1_rad,theta2_rad,w1_rad_s,w2_rad_s,s_m,delta_m,region,pairs,normal_force_N,
// friction_force_N (docs/usage.md, "Output columns").
Columns<SeriesRow> series_columns();
std::string series_csv(const std::vector<SeriesRow>& rows);
// The same in pieces, for a series streamed to its file as the run goes: the
// header line, and one row appended to `out`.
std::string series_csv_header();
void append_series_row(std::string& out, const SeriesRow& row);
// The planar series of a case with elastic bearings (SimulationResult::
// planar_series), in pieces as the series: t_s, the positions x1_m, y1_m,
// theta1_rad, x2_m, y2_m, theta2_rad, their rates (vx1_m_s, ..., w2_rad_s),
// the motor's and the load's angles and speeds (their gears' without shafts),
// the force each bearing exerts on its gear (bearing_fx1_N, ...), the normal
// forces of each side (drive_force_N, coast_force_N) and their penetrations;
// with `helical` (a helical pair's run) then axial_force1_N, axial_force2_N,
// tilting_moment1_N_m and tilting_moment2_N_m, reported only.
Columns<PlanarRow> planar_series_columns(bool helical = false);
std::string planar_series_csv_header(bool helical = false);
void append_planar_row(std::string& out, const PlanarRow& row, bool helical = false);
// The samples of RunControl::sample_rate_hz, in pieces as the series:
// t_s,theta1_rad,theta2_rad,w1_rad_s,w2_rad_s,w1_dot_rad_s2,w2_dot_rad_s2,s_m,dte_m,
// normal_force_n1_N,normal_force_n2_N,region,pairs
Columns<SampleRow> sample_columns();
std::string samples_csv_header();
void append_sample_row(std::string& out, const SampleRow& row);
// The samples of a planar run (SimulationResult::planar_samples), in pieces
// as the series: t_s, the state as the planar series names it (x1_m, ...,
// w_load_rad_s), the accelerations ax1_m_per_s2, ay1_m_per_s2,
// alpha1_rad_per_s2, ax2_m_per_s2, ay2_m_per_s2, alpha2_rad_per_s2, the
// bearing forces (bearing_fx1_N, ...), dte_m, drive_force_N, coast_force_N
// and sensor_acceleration_m_per_s2.
Columns<PlanarSample> planar_sample_columns();
std::string planar_samples_csv_header();
void append_planar_sample(std::string& out, const PlanarSample& sample);
// The summary as a JSON object.
std::string summary_json(const SimulationSummary& summary);
// The columns of a gear train's series (TrainRow): t_s; per body, in the train's order,
// theta_BODY_rad and w_BODY_rad_per_s; per mesh, s_MESH_m, delta_MESH_m, region_MESH,
// pairs_MESH, normal_force_MESH_N and friction_force_MESH_N (BODY and MESH the names of the
// case file); then per body on elastic bearings x_BODY_m, y_BODY_m, bearing_fx_BODY_N and
// bearing_fy_BODY_N, and with a sensor (GearTrain::sensor_body) sensor_acceleration_m_per_s2.
// Integral columns (region, pairs) are written as integers.
using TrainColumn = Column<TrainRow>;
Columns<TrainRow> train_series_columns(const GearTrain& train);
// The series as CSV by those columns: a header line, a row each, numbers at 17 digits.
std::string train_series_csv(const GearTrain& train, const std::vector<TrainRow>& rows);
// The run's summary as a JSON object: the train's counts and energy ledger (its residual
// ledger_residual_max_J among them; with bodies on bearings, their stored energy at the start
// and end and their dampers' loss), then "meshes": per mesh its name, impacts, largest
// penetration, damping_loss_J and friction_loss_J (and mesh_damper_loss_J for a mesh with a
// mesh damper), then "bodies": per body its name and final_w_rad_per_s.
std::string train_summary_json(const GearTrain& train, const TrainResult& result);
// A planetary stage's summary.json (train_summary_json's keys, then "stage": the mean speeds of
// the sun, ring and carrier and the Willis residual of planetary_willis).
std::string stage_summary_json(const GearTrain& train, const TrainResult& result,
                               const StageWillis& willis);
// The ring-housing sensor's series (planetary_ring_sensor): t_s and ring_sensor_y_N per row.
std::string ring_sensor_csv(const std::vector<TrainRow>& rows, const std::vector<double>& y);
// A stage's tooth identity on its run (planetary_teeth_series), one row each: t_s, then per
// planet n sun_tooth_at_sun_planetN, planetN_tooth_at_sun_planetN, planetN_tooth_at_ring_planetN
// and ring_tooth_at_ring_planetN, each a tooth number in the stage's count, as an integer.
Columns<StageTeethRow> stage_teeth_columns(std::size_t planets);
std::string stage_teeth_csv(std::size_t planets, const std::vector<StageTeethRow>& rows);
// A tacho's edges, one row each: pulse,t_s,t_emitted_s, the true (jitter-free)
// time and the emitted one (with the seeded jitter; equal without).
std::string tacho_csv(const std::vector<double>& true_times_s,
                      const std::vector<double>& emitted_times_s);
// A driven run's struck impacts (struck_impacts), one row each:
// t_s,flank,impact_speed_m_s with flank N1 (drive) or N2 (back).
std::string rattle_impacts_csv(const std::vector<ImpactRecord>& struck);
// Its columns, described once.
Columns<ImpactRecord> rattle_impact_columns();
// lower_m_s,upper_m_s,count_n1,count_n2,count: one row per bin of
// impact_speed_histogram, its edges and its impacts on each flank and both.
std::string impact_speed_histogram_csv(const ImpactSpeedHistogram& histogram);
// Fig. 7: f,ratio_case1,ratio_case2,... (friction loss / damping loss).
std::string friction_sweep_csv(const std::vector<SweepRow>& rows);
// Fig. 8: angle_deg,pairs,hertz_over_bending_one_pair,...
std::string energy_ratios_csv(const std::vector<EnergyRatios>& rows);
// The stiffness columns after x_m and phi1_rad, in their order: the paper's
// per-tooth terms gear by gear, the per-pair terms, ke, then the later
// per-tooth terms term by term (kb1,ka1,kb2,ka2,kh,ke,ks1,ks2,kf1,kf2). The
// one list the CSV writer and the Python package both follow.
struct StiffnessColumn {
  std::string name;
  std::optional<Term> term;  // empty: ke
  Gear gear = Gear::one;
};
std::vector<StiffnessColumn> stiffness_columns();
// A column's value, N/m: the term's stiffness (inf where the model switches it
// off or does not have it), or Ke.
double stiffness_column_value(const StiffnessColumn& column, const MeshStiffness& k,
                              const StiffnessModel& model);

// x_m,phi1_rad,kb1,ka1,kb2,ka2,kh,ke,ks1,ks2,kf1,kf2: the stiffness of every
// term, N/m, and Ke at each X1 (17 significant digits); inf for a term that
// is switched off or that the model does not have.
std::string stiffness_csv(const GearPair& pair, const StiffnessModel& model,
                          const std::vector<double>& x1_m);
// One mesh period: fraction,theta1_rad,pairs,ke_n_per_m.
std::string mesh_stiffness_csv(const TimeVaryingMeshStiffness& tvms);
// The true period of a mesh whose teeth may differ (true_period_mesh_stiffness, one mesh
// period without faults, with the same first four columns as mesh_stiffness_csv to the bit):
// fraction,theta1_rad,pairs,ke_n_m,healthy_ke_n_m, then for each of the most pairs in contact
// pairJ_pinion_tooth,pairJ_wheel_tooth,pairJ_ke_n_m (empty cells where fewer pairs are in
// contact); pair 1 is the one nearest the start of contact (the last to enter).
std::string true_period_mesh_stiffness_csv(const TruePeriodMeshStiffness& tvms);
// Its columns, described once (the CSV writer and the Python package's arrays follow them), for
// a period whose samples have at most `most_pairs` pairs in contact (most_pairs_in_contact).
Columns<TruePeriodSample> true_period_mesh_stiffness_columns(std::size_t most_pairs);
std::size_t most_pairs_in_contact(const TruePeriodMeshStiffness& tvms);
// min_n_m, max_n_m, mean_n_m (the exact time mean over the true period), contact_ratio,
// period (its kind), mesh_periods, min_at_fraction, max_at_fraction (of the true period),
// healthy_mean_n_m (the same pairs all healthy), simulation_theta1_offset_rad, extrapolated
// (the foundation fit used outside its range) and, when it is, a warning naming each gear,
// parameter, value and the fit's range.
// A helical pair's mesh stiffness over one mesh period (docs/helical.md):
// fraction,theta1_rad,k_slices_n_m,k_face_n_m,contact_line_length_m,
// contact_line_length_slices_m; and its summary (extremes, the exact mean,
// the contact ratios, ISO's c_gamma_alpha b) as JSON.
// Its columns, described once (the CSV writer and the Python package's arrays follow them).
Columns<HelicalMeshStiffnessSample> helical_mesh_stiffness_columns();
std::string helical_mesh_stiffness_csv(const HelicalMeshStiffnessCurve& curve);
std::string helical_mesh_stiffness_summary_json(const HelicalMeshStiffnessCurve& curve);

std::string true_period_mesh_stiffness_summary_json(const TruePeriodMeshStiffness& tvms,
                                                    double contact_ratio);
// zn1, zn2, c_prime_th_n_mm_um, c_prime_n_mm_um, c_gamma_alpha_n_mm_um,
// eps_alpha, c_prime_b_n_per_m, c_gamma_alpha_b_n_per_m (c' and c_gamma_alpha times
// the face width b); with a specific load F_t K_A / b (N/m), also specific_load_n_mm and
// low_load_factor (1 from 100 N/mm up), which c_prime and c_gamma_alpha then include.
std::string iso6336_json(const Iso6336Stiffness& iso, double face_width_m,
                         std::optional<double> specific_load_n_per_m = std::nullopt);

// The static transmission error, one row per pinion angle:
// theta1_rad,theta1_deg,ste_m,kte_m,effective_stiffness_n_per_m,pairs,loaded_pairs,
// share_1..share_4,gap_1..gap_4 (the pairs within the contact segment in ascending X, the
// newest first; empty beyond `pairs`), teeth ("pinion/wheel" of each, space-separated, in the
// same order). ste_m and effective_stiffness_n_per_m are empty where no pair carries the load
// (StePoint::carried: every pair in the segment has a missing tooth).
std::string ste_csv(const StaticTransmissionError& ste);
// Its columns, described once (the CSV writer and the Python package's arrays follow them).
Columns<StePoint> ste_columns();
// The same points pair by pair: one block per pair of teeth (in the order the
// pairs enter), each row a point where the pair is in the contact segment,
// blocks separated by two empty lines so that gnuplot reads each pair as one
// data set. Columns: pair (its mesh index k), pinion_tooth, wheel_tooth,
// theta1_deg, share (F_k / F), gap_m, stiffness_n_per_m.
std::string ste_pairs_csv(const StaticTransmissionError& ste);
// torque1_n_m, force_n, mesh_periods, period_rad, points, quasi_static_force_ratio and
// unmodified_quasi_static_force_ratio (quasi_static_peak_force_ratio of each pair, the zero-speed
// limit of a run's largest mesh force over F), then for the modified pair and the
// same pair unmodified (unmodified_ prefix): ste_mean_m, ste_min_m, ste_max_m,
// ste_peak_to_peak_m, kte_peak_to_peak_m, least_effective_stiffness_n_per_m (over the carried
// points), uncarried_points.
std::string ste_summary_json(const StaticTransmissionError& modified,
                             const StaticTransmissionError& unmodified,
                             double quasi_static_force_ratio,
                             double unmodified_quasi_static_force_ratio);

// A helical pair's loaded STE (`ste` on a helical pair, docs/helical.md): one row per angle
// (theta1_rad, theta1_deg, ste_m, kte_m, effective_stiffness_n_per_m, elements,
// loaded_elements, load_centre_m, face_load_factor).
Columns<HelicalStePoint> helical_ste_columns();
std::string helical_ste_csv(const HelicalStaticTransmissionError& ste);
// The load across the face, one row per slice: y_m, the mean load per unit face width wbar
// of the modified and the unmodified pair (N/m, over the true period), and each over F_bt / b.
std::string helical_face_load_csv(const HelicalStaticTransmissionError& modified,
                                  const HelicalStaticTransmissionError& unmodified);
// torque1_n_m, force_n, mesh_periods, period_rad, points, face_slices, route, then for the
// modified and the unmodified pair the STE's mean, least, largest and peak-to-peak, the KTE's
// range, K_Hbeta (from wbar), the largest K_Hbeta(theta) and the load centre y_c.
std::string helical_ste_summary_json(const HelicalStaticTransmissionError& modified,
                                     const HelicalStaticTransmissionError& unmodified);

}  // namespace gearimpact

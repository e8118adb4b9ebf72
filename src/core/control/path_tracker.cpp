#include "lane_keeping/control/path_tracker.h"

#include <cmath>

#include <random>

namespace lane_keeping {

PathTracker::PathTracker(const TrackerParams& params, std::shared_ptr<const Path> path)
    : params_(params), path_(std::move(path)) {
  buildExcitation();
}

void PathTracker::setParams(const TrackerParams& params) {
  params_ = params;
  buildExcitation();
}

void PathTracker::buildExcitation() {
  excitation_frequency_.clear();
  excitation_phase_.clear();
  excitation_amplitude_.clear();
  if (params_.excitation_amplitude > 0.0) {
    // Log-spaced frequencies, random phases (seeded: reproducible), equal amplitudes scaled so that
    // the multisine's RMS is excitation_amplitude.
    std::mt19937 rng(static_cast<unsigned>(params_.excitation_seed));
    std::uniform_real_distribution<double> phase(0.0, 2.0 * M_PI);
    const int n = params_.excitation_components;
    const double f0 = params_.excitation_min_frequency, f1 = params_.excitation_max_frequency;
    for (int k = 0; k < n; ++k) {
      excitation_frequency_.push_back(n == 1 ? f0 : f0 * std::pow(f1 / f0, static_cast<double>(k) / (n - 1)));
      excitation_phase_.push_back(phase(rng));
      excitation_amplitude_.push_back(params_.excitation_amplitude * std::sqrt(2.0 / n));
    }
  }
}

SteeringCommand PathTracker::excitation(double t) const {
  SteeringCommand e;
  for (std::size_t k = 0; k < excitation_frequency_.size(); ++k) {
    const double w = 2.0 * M_PI * excitation_frequency_[k];
    e.delta_des += excitation_amplitude_[k] * std::sin(w * t + excitation_phase_[k]);
    e.delta_des_rate += excitation_amplitude_[k] * w * std::cos(w * t + excitation_phase_[k]);
  }
  return e;
}

std::vector<PathTracker::ExcitationComponent> PathTracker::excitationComponents() const {
  std::vector<ExcitationComponent> out;
  for (std::size_t k = 0; k < excitation_frequency_.size(); ++k) {
    out.push_back({excitation_frequency_[k], excitation_phase_[k], excitation_amplitude_[k]});
  }
  return out;
}

SteeringCommand PathTracker::command(const PoseSample& pose, double t, PathErrors* errors) const {
  SteeringCommand c = command(pose, errors);
  if (!excitation_frequency_.empty()) {
    const SteeringCommand e = excitation(t + params_.excitation_clock_offset);
    c.delta_des += e.delta_des;
    c.delta_des_rate += e.delta_des_rate;
  }
  return c;
}

SteeringCommand PathTracker::command(const PoseSample& pose, PathErrors* errors) const {
  // The tracker sees the pose through its localisation, with the configured bias (0 by default).
  double bias_scale = 1.0;
  if (params_.pose_bias_variation != 0.0) {
    bias_scale += params_.pose_bias_variation * std::sin(2.0 * M_PI * pose.x / params_.pose_bias_wavelength);
  }
  const PathErrors e = path_->errors(pose.x, pose.y + bias_scale * params_.pose_bias_y,
                                     pose.psi + bias_scale * params_.pose_bias_psi, pose.x_dot, pose.y_dot, pose.yaw_rate);
  if (errors != nullptr) *errors = e;
  SteeringCommand command;
  command.delta_des = -params_.k_psi * std::sin(e.heading) - params_.k_y * e.lateral;                            // eq 11
  command.delta_des_rate = -params_.k_psi * std::cos(e.heading) * e.heading_rate - params_.k_y * e.lateral_rate;  // d/dt eq 11
  return command;
}

}  // namespace lane_keeping

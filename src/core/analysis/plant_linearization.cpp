#include "lane_keeping/analysis/plant_linearization.h"

#include <cmath>
#include <sstream>

#include <ceres/jet.h>

#include "lane_keeping/common/errors.h"

namespace lane_keeping {
namespace {

using Jet = ceres::Jet<double, 1>;

}  // namespace

std::vector<std::string> plantStateNames(const SingleTrackModel& model) {
  std::vector<std::string> names = {"x", "y", "psi", "delta", "sigma1", "sigma2", "sigma3"};
  for (int i = kRigidStateSize; i < model.frontTireOffset(); ++i) {
    names.push_back("steering[" + std::to_string(i - kRigidStateSize) + "]");
  }
  for (int i = model.frontTireOffset(); i < model.rearTireOffset(); ++i) {
    names.push_back("front_tire[" + std::to_string(i - model.frontTireOffset()) + "]");
  }
  for (int i = model.rearTireOffset(); i < model.stateSize(); ++i) {
    names.push_back("rear_tire[" + std::to_string(i - model.rearTireOffset()) + "]");
  }
  return names;
}

Eigen::MatrixXd PlantLinearization::poseJacobian() const {
  // VehiclePlant::pose() = {x, y, psi, x_dot, y_dot, sigma2}; x_dot and y_dot are rows kX, kY of
  // the model derivative (eq 2), which do not depend on the torque.
  Eigen::MatrixXd p = Eigen::MatrixXd::Zero(6, size());
  p(0, kX) = 1.0;
  p(1, kY) = 1.0;
  p(2, kPsi) = 1.0;
  p.row(3) = a.row(kX);
  p.row(4) = a.row(kY);
  p(5, kSigma2) = 1.0;
  return p;
}

PlantLinearization linearizePlant(const SingleTrackModel& model) {
  const int n = model.stateSize();
  PlantLinearization lin;
  lin.equilibrium = model.initialState(InitialState{0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0});
  lin.a.resize(n, n);
  lin.b.resize(n);
  lin.drift.resize(n);
  lin.mass = model.massMatrix(0.0);
  lin.state_names = plantStateNames(model);

  // One forward-mode pass per column (n + 1 passes of the model; Jet<double, 1> keeps it general
  // in the number of tire states).
  std::vector<Jet> x(n), x_dot(n);
  for (int column = 0; column <= n; ++column) {
    for (int i = 0; i < n; ++i) x[i] = i == column ? Jet(lin.equilibrium[i], 0) : Jet(lin.equilibrium[i]);
    const Jet torque = column == n ? Jet(0.0, 0) : Jet(0.0);
    for (auto& v : x_dot) v = Jet(0.0);
    model.derivative(x.data(), torque, x_dot.data());
    for (int i = 0; i < n; ++i) {
      const double slope = x_dot[i].v[0];
      if (!std::isfinite(slope) || !std::isfinite(x_dot[i].a)) {
        throw ModelError("linearisation: d(" + lin.state_names[i] + ")/dt is not finite at straight-line motion");
      }
      if (column < n) {
        lin.a(i, column) = slope;
      } else {
        lin.b[i] = slope;
      }
      if (column == 0) lin.drift[i] = x_dot[i].a;
    }
  }

  // Straight-line motion must be an equilibrium: only x moves (at V).
  const double V = model.params().speed;
  for (int i = 0; i < n; ++i) {
    const double expected = i == kX ? V : 0.0;
    if (std::fabs(lin.drift[i] - expected) > 1e-9 * (1.0 + V)) {
      std::ostringstream message;
      message << "linearisation: straight-line motion is not an equilibrium of this configuration: d("
              << lin.state_names[i] << ")/dt = " << lin.drift[i] << " there (expected " << expected
              << "); switch off disturbance.* and steering offsets for the stability analysis";
      throw ModelError(message.str());
    }
  }
  return lin;
}

}  // namespace lane_keeping

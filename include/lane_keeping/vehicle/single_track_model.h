#pragma once
/// Beregi's single-track model of a front-wheel-drive car with a steered front axle:
/// kinematics (eq 2), Appell-Gibbs dynamics (eqs 3-5), slip angles at the leading points of the
/// contact patches (eq 8), and the tire of each axle (any model of tire.h).
///
/// State layout: [x, y, psi, delta, sigma1, sigma2, sigma3 | steering-system states | front tire states |
///                rear tire states]   (steering-system states only when enabled: see steering_params.h)
///   x, y   position of G in map [m];  psi yaw [rad];  delta steering angle [rad]
///   sigma1 lateral velocity of G in the body frame [m/s];  sigma2 yaw rate [rad/s];
///   sigma3 steering rate [rad/s]  (Beregi's pseudo-velocities)
/// Input: the steering torque command M_S [N m] (through the steering system of steering_params.h,
/// which is Beregi's rigid, frictionless f3 = M_F + M_S unless configured otherwise). The speed V of the front axle along its wheel is held
/// constant by the non-holonomic constraint (eq 1); the traction force that does so is the
/// constraint force and does not appear. V may also vary: along the road (vehicle.speed_variation), in
/// time (vehicle.speed_profile, which the runner imposes at each evaluation's time: followSpeedProfile),
/// or as logged (setSpeed); a varying V adds the rheonomic terms of bodyForces.
///
/// Eqs 3-5 agree term by term with an independent Gibbs-Appell derivation (docs/findings.md).
/// Eq 8 (front) divides the contact-patch term a (sigma2 + sigma3) by V cos(delta); the kinematics
/// of the leading point give V. We keep the printed form (it differs only at second order in delta).
#include <cmath>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "lane_keeping/common/scalar.h"
#include "lane_keeping/common/sin_cos.h"
#include "lane_keeping/sim/simulation_params.h"
#include "lane_keeping/tire/tire.h"
#include "lane_keeping/vehicle/speed_profile.h"
#include "lane_keeping/vehicle/steering_params.h"
#include "lane_keeping/vehicle/vehicle_params.h"

namespace lane_keeping {

enum RigidState : int { kX = 0, kY, kPsi, kDelta, kSigma1, kSigma2, kSigma3, kRigidStateSize };

/// Everything a user may want to see at one instant (SI; angles in rad).
template <typename T>
struct VehicleOutputs {
  T x_dot{0.0}, y_dot{0.0};               ///< velocity of G in map
  T longitudinal_velocity{0.0};           ///< u, body-frame forward velocity of G
  T lateral_acceleration{0.0};            ///< a_y = d(sigma1)/dt + sigma2 u, body frame, at G
  T sigma_dot[3] = {T(0.0), T(0.0), T(0.0)};
  T tan_slip_front{0.0}, tan_slip_rear{0.0};  ///< tan(alpha_F), tan(alpha_R), Beregi eq 8
  TireForces<T> front, rear;
};

class SingleTrackModel {
 public:
  SingleTrackModel(const VehicleParams& params, Tire front, Tire rear);
  SingleTrackModel(const VehicleParams& params, const SteeringParams& steering, const DisturbanceParams& disturbance,
                   Tire front, Tire rear);

  int stateSize() const { return state_size_; }
  /// Steering-system states: column angle and rate (if compliant), then the LuGre friction state.
  int steeringStateOffset() const { return kRigidStateSize; }
  int frontTireOffset() const { return front_offset_; }
  int rearTireOffset() const { return rear_offset_; }
  const VehicleParams& params() const { return p_; }
  const SteeringParams& steering() const { return steering_; }
  const DisturbanceParams& disturbance() const { return disturbance_; }
  const Tire& frontTire() const { return front_; }
  const Tire& rearTire() const { return rear_; }

  /// Initial state: the given rigid-body state, tires relaxed (zero deflection).
  Eigen::VectorXd initialState(const InitialState& initial) const;

  /// Generalised mass matrix of eq 4 at steering angle delta.
  Eigen::Matrix3d massMatrix(double delta) const;

  /// State derivative (eqs 2, 3, 5, 8 and the tire state equations) for steering torque M_S.
  template <typename T>
  void derivative(const T* x, const T& steering_torque, T* x_dot, VehicleOutputs<T>* outputs = nullptr) const {
    const Trig<T> steer(x[kDelta]);
    kinematics(x, steer, x_dot);
    const Contacts<T> c = contacts(x, steer);
    const TireForces<T> tf = front_.evaluate(c.front, x + frontTireOffset(), x_dot + frontTireOffset());
    const TireForces<T> tr = rear_.evaluate(c.rear, x + rearTireOffset(), x_dot + rearTireOffset());
    T f1, f2;
    bodyForces(x, steer, tf, tr, &f1, &f2);
    const T f3 = tf.aligning_moment + steeringSystem(x, steering_torque, x_dot);  // eq 5, f3 = M_F + M_S
    solveAccelerations(steer, f1, f2, f3, x_dot + kSigma1);
    if (outputs != nullptr) {
      outputs->x_dot = x_dot[kX];
      outputs->y_dot = x_dot[kY];
      outputs->longitudinal_velocity = c.u;
      outputs->lateral_acceleration = x_dot[kSigma1] + x[kSigma2] * c.u;
      outputs->sigma_dot[0] = x_dot[kSigma1];
      outputs->sigma_dot[1] = x_dot[kSigma2];
      outputs->sigma_dot[2] = x_dot[kSigma3];
      outputs->tan_slip_front = c.front.tan_slip_angle;
      outputs->tan_slip_rear = c.rear.tan_slip_angle;
      outputs->front = tf;
      outputs->rear = tr;
    }
  }

  // ---- The pieces of derivative(), public so that reduced replays (gap diagnosis: steering with
  // ---- the chassis motion given, chassis with the steering angle given) use the same physics.

  /// cos, sin and 1/cos of the steering angle, computed once per evaluation.
  template <typename T>
  struct Trig {
    explicit Trig(const T& delta) {
      sinCos(delta, &s, &c);
      inv_c = 1.0 / c;
    }
    T c, s, inv_c;
  };

  /// A speed imposed from outside, for replays of a log whose speed varies (the gap diagnosis): V and
  /// dV/dt at the time of the next evaluations, instead of the configured speed (and its profile, which
  /// must be off: vehicle.speed_variation = 0). dV/dt enters f1, f2 as the rheonomic terms of a varying
  /// speed do (bodyForces).
  void setSpeed(double V, double V_dot) {
    p_.speed = V;
    inv_V_ = 1.0 / V;
    imposed_V_dot_ = V_dot;
  }

  /// vehicle.speed_profile is set: V follows it in time, imposed by whoever knows the time
  /// (followSpeedProfile: the plant at each RK4 stage). Until then V is the profile's first speed.
  bool followsSpeedProfile() const { return speed_profile_ != nullptr; }
  /// Imposes V and dV/dt of vehicle.speed_profile at time t [s] from the run's start (setSpeed); nothing
  /// without a profile.
  void followSpeedProfile(double t) {
    if (!speed_profile_) return;
    const SpeedProfile::Sample s = speed_profile_->at(t);
    setSpeed(s.speed, s.rate);
  }

  /// Eq 2: x_dot[kX], x_dot[kY], x_dot[kPsi], x_dot[kDelta].
  /// Speed of the front axle V at the position x (constant unless vehicle.speed_variation > 0).
  template <typename T>
  T speedAt(const T* x) const {
    using std::sin;
    if (p_.speed_variation == 0.0) return T(p_.speed);
    return p_.speed * (1.0 + p_.speed_variation * sin(speed_k_ * x[kX]));
  }

  template <typename T>
  void kinematics(const T* x, const Trig<T>& steer, T* x_dot) const {
    const double b = p_.cgToFrontAxle();
    const T V = speedAt(x);
    const T& c = steer.c;
    const T& s = steer.s;
    const T& inv_c = steer.inv_c;
    T sp, cp;
    sinCos(x[kPsi], &sp, &cp);
    const T tan_d = s * inv_c;
    // sin(psi + delta) and cos(psi + delta) by the addition theorems.
    const T s_pd = sp * c + cp * s;
    const T c_pd = cp * c - sp * s;
    const T& s1 = x[kSigma1];
    const T& s2 = x[kSigma2];
    x_dot[kX] = V * cp * inv_c - s1 * s_pd * inv_c - s2 * b * cp * tan_d;
    x_dot[kY] = V * sp * inv_c + s1 * c_pd * inv_c - s2 * b * sp * tan_d;
    x_dot[kPsi] = s2;
    x_dot[kDelta] = x[kSigma3];
  }

  template <typename T>
  struct Contacts {
    ContactKinematics<T> front, rear;
    T u;  ///< body-frame forward velocity of G (row 1 of eq 1)
  };

  /// Eq 8 slip angles at the leading points Q (front) and P (rear), Deur slip speeds at the centres.
  template <typename T>
  Contacts<T> contacts(const T* x, const Trig<T>& steer) const {
    const double d = p_.cg_to_rear_axle, b = p_.cgToFrontAxle();
    const T V = speedAt(x);
    const T inv_V = p_.speed_variation == 0.0 ? T(inv_V_) : T(1.0 / V);
    const T& s1 = x[kSigma1];
    const T& s2 = x[kSigma2];
    const T& s3 = x[kSigma3];
    const T& s = steer.s;
    const T& inv_c = steer.inv_c;
    const T front_lateral = s1 + b * s2;  // lateral velocity of F in the body frame
    Contacts<T> out;
    const T u_cos = V - front_lateral * s;  // u cos(delta)
    out.u = u_cos * inv_c;
    const T inv_u = steer.c / u_cos;  // the one division of the rear slip angle, kept for the rear tire
    const double aF = front_half_length_, aR = rear_half_length_;
    out.front.tan_slip_angle = -(front_lateral + aF * (s2 + s3)) * inv_c * inv_V + s * inv_c;
    out.front.wheel_speed = V;
    out.front.inv_wheel_speed = inv_V;
    out.front.lateral_slip_speed = V * s * inv_c - front_lateral * inv_c;  // -(lateral velocity of F across the wheel)
    out.front.yaw_rate = s2 + s3;
    out.rear.tan_slip_angle = -(s1 - (d - aR) * s2) * inv_u;
    out.rear.wheel_speed = out.u;
    out.rear.inv_wheel_speed = inv_u;
    out.rear.lateral_slip_speed = -(s1 - d * s2);
    out.rear.yaw_rate = s2;
    return out;
  }

  /// The disturbance's lateral force at the state x [N] (with its gust): what an accelerometer does not
  /// sense when it is a road bank's gravity component (DisturbanceParams::kind).
  double unsensedLateralForce(const double* x) const {
    if (!unsensed_disturbance_) return 0.0;
    double scale = disturbance_.onsetScale(x[kX]);
    if (disturbance_.gust_amplitude != 0.0) {
      scale *= 1.0 + disturbance_.gust_amplitude * std::sin(2.0 * M_PI * x[kX] / disturbance_.gust_wavelength);
    }
    return scale * disturbance_.lateral_force;
  }

  /// Eq 5: f1 and f2 (plus the optional disturbance on the body).
  template <typename T>
  void bodyForces(const T* x, const Trig<T>& steer, const TireForces<T>& tf, const TireForces<T>& tr, T* f1,
                  T* f2) const {
    using std::cos;
    using std::sin;
    const double d = p_.cg_to_rear_axle, b = p_.cgToFrontAxle();
    const T V = speedAt(x);
    const double m = p_.mass, mF = p_.steering_mass;
    const T& s1 = x[kSigma1];
    const T& s2 = x[kSigma2];
    const T& s3 = x[kSigma3];
    const T& s = steer.s;
    const T& inv_c = steer.inv_c;
    const T inv_c3 = inv_c * inv_c * inv_c;
    const T steer_term = (mF + m) * s * inv_c3 * (V * s - s1 - b * s2) * s3;
    *f1 = tf.lateral_force * inv_c + tr.lateral_force + inv_c * (-(mF + m) * V + m * s2 * b * s) * s2 + steer_term;
    *f2 = tf.aligning_moment + tr.aligning_moment + b * tf.lateral_force * inv_c - d * tr.lateral_force -
          b * inv_c * (mF * V + m * s1 * s) * s2 + b * steer_term;
    if (p_.speed_variation != 0.0) {
      // A varying speed makes the constraint of eq 1 rheonomic: extra inertial terms in f1, f2 (our
      // Gibbs-Appell derivation, docs/findings.md): Vdot (m + m_F) sin(delta) / cos^2(delta) times (1, l - d).
      // Vdot = dV/dx x_dot, with x_dot = u cos(psi) - sigma1 sin(psi) and u from row 1 of eq 1.
      const T u = (V - (s1 + b * s2) * s) * inv_c;
      const T x_dot = u * cos(x[kPsi]) - s1 * sin(x[kPsi]);
      const T V_dot = p_.speed * p_.speed_variation * speed_k_ * cos(speed_k_ * x[kX]) * x_dot;
      const T term = V_dot * (mF + m) * s * inv_c * inv_c;
      *f1 = *f1 + term;
      *f2 = *f2 + b * term;
    } else if (imposed_V_dot_ != 0.0) {  // the same terms with dV/dt imposed (setSpeed)
      const T term = imposed_V_dot_ * (mF + m) * s * inv_c * inv_c;
      *f1 = *f1 + term;
      *f2 = *f2 + b * term;
    }
    if (disturbance_.active()) {
      // A force at G across the body does work on sigma1 only; gusts vary along the road.
      T scale = disturbance_.onsetScale(x[kX]);
      if (disturbance_.gust_amplitude != 0.0) {
        scale = scale * (1.0 + disturbance_.gust_amplitude * sin(2.0 * M_PI * x[kX] / disturbance_.gust_wavelength));
      }
      *f1 = *f1 + scale * disturbance_.lateral_force;
      *f2 = *f2 + scale * disturbance_.yaw_moment;
    }
  }

  /// Eqs 3-4: sigma_dot = M(delta)^-1 f. Row 3 gives sigma3_dot = f3/J_F - sigma2_dot; substituting it
  /// leaves a 2x2 system with determinant m11 (m22 - J_F) - m12^2 > 0.
  template <typename T>
  void solveAccelerations(const Trig<T>& steer, const T& f1, const T& f2, const T& f3, T* sigma_dot) const {
    const double b = p_.cgToFrontAxle(), m = p_.mass, mF = p_.steering_mass, JG = p_.yaw_inertia;
    const T& s = steer.s;
    const T inv_c2 = steer.inv_c * steer.inv_c;
    const T m11 = (mF + m) * inv_c2;
    const T mixed = (mF + m * s * s) * inv_c2;
    const T m12 = mixed * b;
    const T m22_minus_JF = JG + mixed * b * b;
    const T inv_det = 1.0 / (m11 * m22_minus_JF - m12 * m12);
    const T rhs2 = f2 - f3;
    sigma_dot[0] = (f1 * m22_minus_JF - m12 * rhs2) * inv_det;
    sigma_dot[1] = (m11 * rhs2 - m12 * f1) * inv_det;
    sigma_dot[2] = f3 * inv_JF_ - sigma_dot[1];
  }

  /// Rows 1-2 of eq 3 with the steering motion prescribed (delta, its rate in x[kSigma3] and its
  /// acceleration given): m11 s1' + m12 s2' = f1,  m12 s1' + m22 s2' = f2 - J_F delta''.
  template <typename T>
  void solveChassisAccelerations(const Trig<T>& steer, const T& f1, const T& f2, const T& delta_acceleration,
                                 T* sigma_dot) const {
    const double b = p_.cgToFrontAxle(), m = p_.mass, mF = p_.steering_mass, JG = p_.yaw_inertia;
    const double JF = p_.steering_inertia;
    const T& s = steer.s;
    const T inv_c2 = steer.inv_c * steer.inv_c;
    const T m11 = (mF + m) * inv_c2;
    const T mixed = (mF + m * s * s) * inv_c2;
    const T m12 = mixed * b;
    const T m22 = JF + JG + mixed * b * b;
    const T rhs2 = f2 - JF * delta_acceleration;
    const T inv_det = 1.0 / (m11 * m22 - m12 * m12);
    sigma_dot[0] = (f1 * m22 - m12 * rhs2) * inv_det;
    sigma_dot[1] = (m11 * rhs2 - m12 * f1) * inv_det;
  }

  /// Torque the steering system passes to the front axle (f3 without M_F), and the derivatives of
  /// its own states. Beregi's rigid, frictionless steering returns the command unchanged.
  template <typename T>
  T steeringSystem(const T* x, const T& command, T* x_dot) const {
    if (plain_steering_) return command;
    using std::abs;
    using std::exp;
    using std::tanh;
    const SteeringParams& p = steering_;
    T applied = command;
    if (p.dead_band > 0.0) {
      const double cv = toDouble(command);
      applied = std::fabs(cv) <= p.dead_band ? T(0.0) : T(command - sign(command) * p.dead_band);
    }
    if (p.torque_limit > 0.0) {
      if (soft_saturation_) {
        // A smooth clamp: M / (1 + (M / limit)^4)^(1/4) (equals M well below the limit, tends to it).
        using std::pow;
        using std::sqrt;
        const T r = applied / p.torque_limit;
        const T r2 = r * r;
        applied = applied / sqrt(sqrt(1.0 + r2 * r2));
      } else {
        const double av = toDouble(applied);
        if (av > p.torque_limit) applied = T(p.torque_limit);
        if (av < -p.torque_limit) applied = T(-p.torque_limit);
      }
    }
    const T& rate = x[kSigma3];
    int next = steeringStateOffset();
    T transmitted = applied;
    if (p.compliant()) {
      const T& column = x[next];
      const T& column_rate = x[next + 1];
      const T twist = column - x[kDelta];
      T spring = p.column_stiffness * twist;
      if (p.column_stiffening_angle > 0.0) {
        // A progressive torsion bar: k twist (1 + (twist / angle)^2).
        const T r = twist / p.column_stiffening_angle;
        spring *= 1.0 + r * r;
      }
      transmitted = spring + p.column_damping * (column_rate - rate);
      x_dot[next] = column_rate;
      x_dot[next + 1] = (applied - transmitted) / p.column_inertia;
      next += 2;
    }
    T friction(0.0);
    if (lugre_friction_) {
      // LuGre point friction (Deur eqs 6 and 9) on the steering rate.
      const T& z = x[next];
      const T g = p.lugreLevel(rate);
      const T z_dot = rate - p.friction_stiffness * abs(rate) * z / g;
      x_dot[next] = z_dot;
      friction = p.friction_stiffness * z + p.friction_damping * z_dot + p.viscous_friction * rate;
    } else if (p.hasFriction()) {
      friction = p.coulomb_friction * tanh(rate / p.friction_velocity) + p.viscous_friction * rate;
    }
    return transmitted - friction;
  }

 private:
  VehicleParams p_;
  SteeringParams steering_;
  DisturbanceParams disturbance_;
  // The parameters' string-valued choices, read once: derivative() runs millions of times per closed
  // loop, and comparing the friction model's name there was 4 % of a column's bounded refit.
  bool plain_steering_;
  bool soft_saturation_;
  bool lugre_friction_;        ///< steering_.lugreFriction()
  bool unsensed_disturbance_;  ///< an active disturbance the accelerometer does not sense (a road bank)
  Tire front_;
  Tire rear_;
  double inv_V_;   ///< 1 / V
  double inv_JF_;  ///< 1 / J_F
  double speed_k_; ///< 2 pi / speed_wavelength
  double imposed_V_dot_ = 0.0;  ///< [m/s^2] dV/dt imposed by setSpeed (0: none)
  std::shared_ptr<const SpeedProfile> speed_profile_;  ///< vehicle.speed_profile (null: none); shared by copies
  int front_offset_, rear_offset_, state_size_;  ///< state layout, fixed at construction
  double front_half_length_, rear_half_length_;  ///< a of eq 8's leading points (the tires' contactHalfLength())
};

/// Builds the model of a configuration: static axle loads (DESIGN §3) and one tire per axle; rigid,
/// frictionless steering and no disturbance (Beregi's model).
SingleTrackModel createVehicleModel(const VehicleParams& vehicle, const TireParams& front, const TireParams& rear);
/// Same with a steering system and body disturbance.
SingleTrackModel createVehicleModel(const VehicleParams& vehicle, const SteeringParams& steering,
                                    const DisturbanceParams& disturbance, const TireParams& front,
                                    const TireParams& rear);

}  // namespace lane_keeping

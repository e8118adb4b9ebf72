#pragma once
/// What the vehicle model hands a tire, and what the tire returns.
///
/// Sign conventions (written once, used everywhere):
///  * Wheel frame: x along the wheel heading, y to the left of it, z up.
///  * Slip angle alpha > 0 when the contact moves to the *right* relative to the wheel heading,
///    i.e. tan(alpha) = -(lateral velocity)/(longitudinal velocity) (Beregi eq 8).
///  * Slip speeds follow Deur eqs 2-3: v_rx = r|w| - v cos(alpha) (0 in free rolling) and
///    v_ry = +v sin(alpha) = -(lateral velocity of the wheel centre). (Velenis eq 28b uses the
///    opposite sign of v_ry; we do not.)
///  * The lateral force is positive to the left, so it has the sign of alpha and of v_ry: it opposes
///    the lateral slip. The aligning moment is positive counter-clockwise (about +z); for small
///    positive alpha it is negative (pneumatic trail behind the centre), as Beregi eq 10.
namespace lane_keeping {

template <typename T>
struct ContactKinematics {
  T tan_slip_angle{0.0};           ///< tan(alpha) at the leading point of the patch, Beregi eq 8 (brush)
  T wheel_speed{0.0};              ///< r|omega| [m/s]: contact-centre speed along the wheel heading (free rolling)
  T longitudinal_slip_speed{0.0};  ///< v_rx [m/s], Deur eq 2 (0 in free rolling)
  T lateral_slip_speed{0.0};       ///< v_ry [m/s] at the contact centre, Deur eq 3
  T yaw_rate{0.0};                 ///< yaw rate of the wheel plane [rad/s] (turn slip of the distributed model)
  /// 1 / wheel_speed when the vehicle model has it anyway (it divides by the rear wheel speed for the
  /// slip angle; the front's is constant): saves the lumped LuGre tire a division. 0 = not given.
  T inv_wheel_speed{0.0};
};

template <typename T>
struct TireForces {
  T lateral_force{0.0};       ///< F [N], left positive (Beregi F_F, F_R; Deur F_y)
  T aligning_moment{0.0};     ///< M [N m], counter-clockwise positive (Beregi M_F, M_R; Deur M_z)
  T longitudinal_force{0.0};  ///< F_x [N] (LuGre only; 0 in free rolling)
};

}  // namespace lane_keeping

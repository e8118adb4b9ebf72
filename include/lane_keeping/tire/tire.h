#pragma once
/// One tire of an axle, whichever model the config names. The models share no base class: each has
/// a templated `evaluate` (so Ceres Jets can differentiate the same code the simulator runs), and
/// this wrapper dispatches over a std::variant. `createTire` is the one registry of model names.
#include <string>
#include <variant>
#include <vector>

#include "lane_keeping/tire/brush_tire.h"
#include "lane_keeping/tire/contact_kinematics.h"
#include "lane_keeping/tire/lugre_distributed_tire.h"
#include "lane_keeping/tire/lugre_lumped_tire.h"
#include "lane_keeping/tire/magic_formula_tire.h"
#include "lane_keeping/tire/tire_params.h"

namespace lane_keeping {

class Tire {
 public:
  using Model = std::variant<BrushTire, LugreLumpedTire, LugreDistributedTire, MagicFormulaTire>;

  /// @param relaxation_length > 0 adds two states: the force and moment lag behind the model's
  /// with time constant relaxation_length / r|w| (a relaxation-length tire, Pacejka §7).
  Tire(std::string name, Model model, double normal_load, double relaxation_length = 0.0);

  const std::string& name() const { return name_; }
  double normalLoad() const { return normal_load_; }
  int stateSize() const { return model_states_ + (relaxation_length_ > 0.0 ? 2 : 0); }
  double relaxationLength() const { return relaxation_length_; }

  /// Forces and the state derivative. `state` and `state_dot` hold stateSize() values.
  /// Always inlined (with the lumped model's evaluate): the vehicle derivative then interleaves the
  /// front and rear tire arithmetic, which are independent (lumped LuGre closed loop 292x -> 306x
  /// real time, issue #2 benchmark).
  template <typename T>
  [[gnu::always_inline]] TireForces<T> evaluate(const ContactKinematics<T>& kinematics, const T* state, T* state_dot) const {
    // One object, returned as it is (no copy of the model's result): a copy made GCC store the fields
    // one by one and load them back 16 bytes at a time, a store-forwarding stall per tire and derivative.
    TireForces<T> forces = evaluateModel(kinematics, state, state_dot);
    if (relaxation_length_ > 0.0) {
      using std::abs;
      const T rate = abs(kinematics.wheel_speed) * inv_relaxation_length_;
      const T& lagged_force = state[model_states_];
      const T& lagged_moment = state[model_states_ + 1];
      state_dot[model_states_] = rate * (forces.lateral_force - lagged_force);
      state_dot[model_states_ + 1] = rate * (forces.aligning_moment - lagged_moment);
      forces.lateral_force = lagged_force;
      forces.aligning_moment = lagged_moment;
    }
    return forces;
  }

  /// The model's own forces and state derivative. A chain of get_if rather than std::visit: visit
  /// calls through a table of function pointers, which keeps the models from being inlined.
  template <typename T>
  [[gnu::always_inline]] TireForces<T> evaluateModel(const ContactKinematics<T>& kinematics, const T* state, T* state_dot) const {
    if (const auto* lumped = std::get_if<LugreLumpedTire>(&model_)) return lumped->evaluate(kinematics, state, state_dot);
    if (const auto* brush = std::get_if<BrushTire>(&model_)) return brush->evaluate(kinematics, state, state_dot);
    if (const auto* mf = std::get_if<MagicFormulaTire>(&model_)) return mf->evaluate(kinematics, state, state_dot);
    return std::get<LugreDistributedTire>(model_).evaluate(kinematics, state, state_dot);
  }

  /// Forces after the internal states have settled at constant slip (the static curve).
  TireForces<double> steadyState(const ContactKinematics<double>& kinematics) const;
  /// The settled internal states themselves (stateSize() values), e.g. to start a replay segment.
  void steadyStateVector(const ContactKinematics<double>& kinematics, double* state) const;

  /// Half-length a used for the leading-point slip angle of Beregi eq 8 (brush a; LuGre L/2).
  double contactHalfLength() const;
  /// Small-slip dF/dtan(alpha) [N/rad] and -dM/dtan(alpha) [N m/rad] of the static curve.
  double corneringStiffness() const;
  double aligningStiffness() const;

  const Model& model() const { return model_; }

 private:
  int modelStateSize() const;

  std::string name_;
  Model model_;
  double normal_load_;
  double relaxation_length_;
  double inv_relaxation_length_;
  int model_states_;
};

/// Builds the model named by params.model for an axle carrying `normal_load` [N].
/// Throws ConfigError for an unknown model name.
Tire createTire(const TireParams& params, double normal_load);

}  // namespace lane_keeping

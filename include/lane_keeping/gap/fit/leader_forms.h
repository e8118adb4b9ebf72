#pragma once
/// The form that reproduces the effect (issue 47, kind 7). Three candidates stand for effects whose shape the
/// project models better than the candidate does: steering_friction fits the smooth tanh law (Coulomb and
/// viscous), where real kingpin friction sticks (LuGre, Deur eq 9: a bristle state that holds the wheel
/// until the torque breaks it away), and torque_limit fits a hard clamp, where an actuator's saturation is
/// often soft (M / (1 + (M / limit)^4)^(1/4)), and cornering_stiffness scales the tires' stiffness, where a
/// patch of another length (inflation, load) changes the aligning stiffness the steering feels by another
/// factor (C ~ k a^2, aligning ~ k a^3). On the open-loop replays the smooth forms remove the gap
/// nearly as well (an 8 N m kingpin friction with plain stick plateaus: tanh's Coulomb 9.5 N m, 95 %
/// held-out shrink), but the corrected closed loop shows no plateau (16 % closed-loop shrink), and the hard
/// clamp cannot both cut an initial correction's torque and let the loop recover.
///
/// Once the verdict names one of them, its leader forms are fitted too, warm-started from the leader's
/// parameters (a parameter the leader lacks from its initial value), and the form that fits the training
/// data better — by at least min_further_shrink of what the leader leaves there, as a further effect must —
/// *and* leaves a smaller held-out gap (a form with a parameter more must earn it), and whose
/// closed loop stays within the logged bounds, stands for the effect in the verdict, its effects and how
/// far. Not in the first round: fitting them for every log would add three fits to every diagnosis (one
/// with LuGre's stiff state) to change what only a leader's closed loop shows. A further effect
/// (forward_selection.cpp) is fitted in its LuGre or soft form too, beside its candidate, and the form takes
/// the candidate's place by the same rule (not the contact patch's length: docs/gap.md).
///
///   effect             form   parameters                          config keys it changes
///   steering_friction  lugre  coulomb (N m), viscous (N m s/rad),  steering.friction_model = lugre,
///                             stiffness (N m/rad: sigma0, the      .coulomb_friction = .breakaway_friction (no
///                             bristles', whose presliding          Stribeck peak), .viscous_friction,
///                             deflection T_c / sigma0 must be      .friction_stiffness
///                             small for the wheel to stick)
///   torque_limit       soft   limit (N m)                          steering.saturation = soft, .torque_limit
///   cornering_stiffness contact_length  front_scale, rear_scale     tire_front/rear.contact_half_length (and an
///                             (the patch's length: C ~ k a^2 and   explicit lugre.contact_length) times the scale;
///                             the aligning stiffness ~ k a^3,      its start: the square roots of the leader's
///                             where the candidate scales k)        stiffness scales
#include <string>
#include <vector>

#include "lane_keeping/gap/diagnosis_options.h"
#include "lane_keeping/gap/fit/candidate_effects.h"
#include "lane_keeping/gap/fit/candidate_fit.h"

namespace lane_keeping {
namespace diagnosis {

/// The forms above, in that order.
const std::vector<CandidateEffect>& leaderForms();

/// Whether `effect` is one of leaderForms() (not a candidate's own form).
bool isLeaderForm(const CandidateEffect& effect);

/// Whether the fit of a leader form `form` stands for the effect in place of the candidate's own fit `own`:
/// better on the training data by min_further_shrink of what `own` leaves there, better held out, and its
/// closed loop not found outside the logged bounds.
bool formStandsFor(const CandidateFit& form, const CandidateFit& own, const DiagnosisOptions& options);

/// The leader's effect in each of its leader forms, fitted from the leader's parameters on the same data
/// and scored; returns the best of them (by training gap) if it beats the leader's training gap by
/// min_further_shrink and its held-out gap, and its closed loop stays within the logged bounds (where the
/// logs let it be checked), else a fit with ok = false. A note says what was compared and what was chosen.
/// Nothing with options.leader_forms off.
CandidateFit refitLeaderForm(const CandidateFit& leader, const FitContext& context, const DiagnosisOptions& options,
                             std::vector<std::string>* notes);

}  // namespace diagnosis
}  // namespace lane_keeping

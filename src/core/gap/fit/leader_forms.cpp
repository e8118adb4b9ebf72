#include "lane_keeping/gap/fit/leader_forms.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <map>

#include "lane_keeping/common/brief_number.h"
#include "lane_keeping/gap/fit/candidate_objective.h"
#include "lane_keeping/gap/fit/closed_loop_checks.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

std::vector<CandidateEffect> buildLeaderForms() {
  std::vector<CandidateEffect> list;
  CandidateEffect lugre;
  lugre.name = "steering_friction";
  lugre.form = "lugre";
  lugre.description = "LuGre kingpin friction (Deur eq 9): the wheel sticks until the torque breaks it away";
  // The level and viscous part in the tanh form's ranges, and the bristles' stiffness sigma0: the stick is
  // a presliding deflection of T_c / sigma0, which must be small beside the wheel's motion for the wheel to
  // stick (a tanh-like spring otherwise). Not known from a nominal that has no LuGre friction: fitted.
  lugre.params = {{"coulomb", "N m", 1.0, 0.02, 200.0, true},
                  {"viscous", "N m s/rad", 0.1, 0.01, 100.0, true, [](const SimConfig& c) { return c.steering.viscous_friction; }},
                  {"stiffness", "N m/rad", 1e4, 1e2, 1e6, true}};
  lugre.subsystems = {"steering"};
  lugre.apply = [](const std::vector<double>& p, SimConfig& c) {
    c.steering.friction_model = "lugre";
    c.steering.coulomb_friction = p[0];
    c.steering.breakaway_friction = p[0];  // no Stribeck peak: one parameter for the level, as tanh's
    c.steering.viscous_friction = p[1];
    c.steering.friction_stiffness = p[2];
  };
  list.push_back(lugre);
  CandidateEffect soft;
  soft.name = "torque_limit";
  soft.form = "soft";
  soft.description = "the steering actuator saturates smoothly";
  soft.params = {{"limit", "N m", 100.0, 0.5, 1e5, true}};
  soft.subsystems = {"steering"};
  soft.profile = true;
  soft.apply = [](const std::vector<double>& p, SimConfig& c) {
    c.steering.saturation = "soft";
    c.steering.torque_limit = p[0];
  };
  list.push_back(soft);
  // A tire's cornering stiffness changes with its contact patch (inflation pressure, load, construction):
  // C ~ k a^2 (brush; the lumped and distributed LuGre alike) and the aligning stiffness ~ k a^3, so a
  // shorter patch also shortens the pneumatic trail, which the steering feels. The candidate scales the
  // stiffness k (C and the aligning stiffness by the same factor) and matches the chassis' forces; the
  // steering's aligning torque, and so the closed loop, it cannot (the candidates' family's shorter patches,
  // a = 0.09 / 0.092 m for 0.1: the scale form leaves a closed-loop gap of 0.085 net of noise, the truth's
  // patch 0.0024). Scales of contact_half_length (and of an explicit LuGre contact length).
  CandidateEffect patch;
  patch.name = "cornering_stiffness";
  patch.form = "contact_length";
  patch.description =
      "the tires' contact patches differ in length (front and rear scales): cornering and aligning stiffness";
  patch.params = {{"front_scale", "", 1.0, 0.2, 5.0, true}, {"rear_scale", "", 1.0, 0.2, 5.0, true}};
  patch.subsystems = {"chassis", "steering"};
  patch.apply = [](const std::vector<double>& p, SimConfig& c) {
    c.tire_front.contact_half_length *= p[0];
    c.tire_rear.contact_half_length *= p[1];
    if (c.tire_front.lugre.contact_length) *c.tire_front.lugre.contact_length *= p[0];
    if (c.tire_rear.lugre.contact_length) *c.tire_rear.lugre.contact_length *= p[1];
  };
  list.push_back(patch);
  return list;
}

/// The leader's parameters carried to a form's start: the same quantities, except a patch's length, whose
/// square the cornering stiffness scales with (C ~ k a^2).
std::vector<double> startFromLeader(const CandidateEffect& form, const std::vector<double>& leader) {
  std::vector<double> start = leader;
  if (form.form == "contact_length") {
    for (double& s : start) s = std::sqrt(std::max(s, 0.0));
  }
  for (std::size_t j = start.size(); j < form.params.size(); ++j) start.push_back(form.params[j].initial);
  return start;
}

}  // namespace

const std::vector<CandidateEffect>& leaderForms() {
  static const std::vector<CandidateEffect> list = buildLeaderForms();
  return list;
}

bool isLeaderForm(const CandidateEffect& effect) {
  for (const CandidateEffect& form : leaderForms()) {
    if (&form == &effect || (form.name == effect.name && form.form == effect.form)) return true;
  }
  return false;
}

bool formStandsFor(const CandidateFit& form, const CandidateFit& own, const DiagnosisOptions& options) {
  return form.ok && form.unbounded_on.empty() && form.train_after < (1.0 - options.min_further_shrink) * own.train_after &&
         form.heldout_after < own.heldout_after;
}

CandidateFit refitLeaderForm(const CandidateFit& leader, const FitContext& context, const DiagnosisOptions& options,
                             std::vector<std::string>* notes) {
  CandidateFit best;
  if (leader.effect == nullptr || !leader.ok || !options.leader_forms) return best;
  std::string compared;
  for (const CandidateEffect& form : leaderForms()) {
    if (form.name != leader.effect->name || form.params.size() < leader.theta.size()) continue;
    if (options.progress) options.progress("fitting " + form.label() + " (the leader's other form)");
    // Warm-started from the leader's parameters: the same quantities in the other shape.
    // A parameter the leader lacks starts from its initial value.
    const std::vector<double> start = startFromLeader(form, leader.theta);
    const std::map<std::string, std::vector<double>> warm{{form.label(), start}};
    FitContext from_leader = context;
    from_leader.warm_start = &warm;
    from_leader.warm_final_steps = search::kLeaderFormPolishSteps;
    CandidateFit fit;
    try {
      fit = fitCandidate(form, from_leader, options);
      if (fit.ok && context.closed_loop_checks && !fit.loop_checked) {
        const CandidateObjective objective(form, *context.nominal, *context.train, options.replay,
                                           context.nominal_train->sigma1, context.available);
        checkClosedLoop(objective, context, &fit);
      }
    } catch (const std::exception& e) {
      fit.ok = false;
      fit.note = std::string("fit failed: ") + e.what();
    }
    compared += ", " + form.form + " " + (fit.ok ? briefNumber(fit.train_after) + " (held-out " + briefNumber(fit.heldout_after) + ")" : "failed") +
                (fit.ok && !fit.unbounded_on.empty() ? " (its closed loop leaves the logged bounds)" : "");
    // Better on the training data by what a further effect must remove of what is left (min_further_shrink:
    // forms the data barely tell apart keep the candidate's own, 0.1813 against 0.1811 on a limit whose soft
    // closed loop was the worse), and on the held-out data too: a form with a parameter more must earn it.
    if (formStandsFor(fit, leader, options) && (!best.ok || fit.train_after < best.train_after)) {
      best = fit;
    }
  }
  if (compared.empty()) return best;
  const std::string leader_form = leader.effect->form.empty() ? "as fitted" : leader.effect->form;
  notes->push_back(leader.effect->name + ": the leader's forms by their training gap (" + leader_form + " " +
                   briefNumber(leader.train_after) + " (held-out " + briefNumber(leader.heldout_after) + ")" + compared + "): " +
                   (best.ok ? best.effect->form + " stands for it (verdict, effects and how far)"
                            : "the leader's form stands"));
  return best;
}

}  // namespace diagnosis
}  // namespace lane_keeping

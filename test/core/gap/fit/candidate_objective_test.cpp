// The candidate objective remembers losses and closed-loop checks (a coordinate search revisits
// points, and under a stability requirement each visit is a closed-loop run): a remembered value must
// be the value, and a loss remembered without a requirement must not answer for one with it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

#include "benchmark_objective_fixture.h"
#include "lane_keeping/gap/fit/bounded_loop.h"
#include "lane_keeping/gap/fit/candidate_objective.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

struct Fixture : BenchmarkObjectiveFixture {
  Fixture() : BenchmarkObjectiveFixture("steering_compliance-small-sinusoid", 6.0, 200.0, 0.5) {}

  BoundedLoopRequirement requirement() const {
    const LogSignals& log = *runs.front().log;
    double angle = 0.0, torque = 0.0;
    for (double d : log.samples(LogSignals::kDelta)) angle = std::max(angle, std::fabs(d));
    for (double t : log.samples(LogSignals::kTorque)) torque = std::max(torque, std::fabs(t));
    return {&log, runs.front().config.get(), log.end() - log.start(), 1.5 * angle + 0.02, 2.0 * torque + 5.0};
  }
};

TEST(CandidateObjective, ARememberedLossIsTheLossAndARequirementIsPartOfIt) {
  const Fixture f;
  const CandidateEffect& column = candidateNamed("steering_compliance", "wheel_sensor");
  CandidateObjective objective = f.objective(column);
  // Stiffness, damping, inertia: a softer column than the truth's, and one whose closed loop rings up
  // within half a second (k = 1.6e5 N m/rad against the actuator's 10 kHz PD loop).
  const std::vector<double> bounded{2000.0, 11.16, 0.0458}, unbounded{164265.0, 11.16, 0.0458};

  const double first = objective.loss(bounded);
  ASSERT_TRUE(std::isfinite(first));
  EXPECT_EQ(objective.loss(bounded), first);
  CandidateObjective fresh = f.objective(column);
  EXPECT_EQ(fresh.loss(bounded), first);
  // A NaN compares equivalent to every number in the memo's ordering: such a point must be evaluated
  // (an invalid configuration), never given the remembered loss of the point it would match.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(std::isfinite(objective.loss({nan, bounded[1], bounded[2]})));

  const double open_loop = objective.loss(unbounded);
  ASSERT_TRUE(std::isfinite(open_loop));
  ASSERT_LT(open_loop, 1e90);  // the replays alone do not rule it out

  const BoundedLoopRequirement r = f.requirement();
  const LoopDivergence d = objective.bounds(unbounded, r);
  ASSERT_TRUE(d.diverged) << "the stiff column's closed loop stayed bounded";
  const LoopDivergence again = objective.bounds(unbounded, r);
  EXPECT_EQ(again.time, d.time);
  EXPECT_EQ(boundsCheck(objective.changeFor(unbounded), r).time, d.time);
  EXPECT_FALSE(objective.bounds(bounded, r).diverged);

  objective.requireStability({r});
  const double required = objective.loss(unbounded);
  EXPECT_GE(required, 1e100) << "a loss remembered without the requirement answered for it";
  EXPECT_DOUBLE_EQ(required, 1e100 * (1.0 + std::clamp(1.0 - d.time / r.horizon, 1e-6, 1.0)));
  EXPECT_EQ(objective.loss(bounded), first);  // bounded: the requirement adds nothing

  objective.requireStability({});
  EXPECT_EQ(objective.loss(unbounded), open_loop);
}

TEST(CandidateObjective, ALossIsRememberedWhenEverythingItIsMadeOfIs) {
  // A constrained line search takes a point whose loss costs nothing alone, before running a batch beside
  // it (the bounded refit runs points' closed loops ahead, bounds() and replayLoss(), not loss()). Such a
  // point is one whose bounds checks under the requirement in force are remembered, up to the first that
  // diverges, and, if none does, its replay loss; and loss() must then run nothing.
  const Fixture f;
  const CandidateEffect& column = candidateNamed("steering_compliance", "wheel_sensor");
  CandidateObjective objective = f.objective(column);
  const std::vector<double> bounded{2000.0, 11.16, 0.0458}, unbounded{164265.0, 11.16, 0.0458};
  const BoundedLoopRequirement r = f.requirement();
  objective.requireStability({r});
  EXPECT_FALSE(objective.remembersLoss(bounded));
  EXPECT_FALSE(objective.remembersLoss(unbounded));

  ASSERT_TRUE(objective.bounds(unbounded, r).diverged) << "the stiff column's closed loop stayed bounded";
  EXPECT_TRUE(objective.remembersLoss(unbounded)) << "a remembered divergence needs no replay";
  ASSERT_FALSE(objective.bounds(bounded, r).diverged);
  EXPECT_FALSE(objective.remembersLoss(bounded)) << "a bounded point's loss is its replay loss, not remembered yet";
  objective.replayLoss(bounded);
  EXPECT_TRUE(objective.remembersLoss(bounded));

  const std::size_t loops = objective.closedLoopRuns(), replays = objective.evaluations();
  EXPECT_EQ(objective.loss(bounded), objective.replayLoss(bounded));
  EXPECT_GE(objective.loss(unbounded), 1e100);
  EXPECT_EQ(objective.closedLoopRuns(), loops);
  EXPECT_EQ(objective.evaluations(), replays) << "a loss said to cost nothing replayed the data";

  // Another requirement is not remembered: the same points must be checked under it.
  BoundedLoopRequirement shorter = r;
  shorter.horizon = 0.5 * r.horizon;
  objective.requireStability({shorter});
  EXPECT_FALSE(objective.remembersLoss(bounded));
  EXPECT_FALSE(objective.remembersLoss(unbounded));
}

TEST(NominalBounds, RemembersTheNominalsLoopPerRequirementAndAnswersAsTheCheckDoes) {
  const Fixture f;
  BoundedLoopRequirement logged = f.requirement();
  BoundedLoopRequirement tight = logged;
  tight.max_steering_angle = 1e-4;  // the nominal's own loop leaves this
  const bool logged_leaves = boundsCheck(nullptr, logged).diverged;
  const bool tight_leaves = boundsCheck(nullptr, tight).diverged;
  ASSERT_FALSE(logged_leaves);
  ASSERT_TRUE(tight_leaves);
  NominalBounds nominal;
  // Asked from two threads at once, each requirement twice: one loop each, the same answers.
  bool answers[2][4];
  std::thread other([&] {
    answers[1][0] = nominal.leaves(logged), answers[1][1] = nominal.leaves(tight);
    answers[1][2] = nominal.leaves(tight), answers[1][3] = nominal.leaves(logged);
  });
  answers[0][0] = nominal.leaves(tight), answers[0][1] = nominal.leaves(logged);
  answers[0][2] = nominal.leaves(logged), answers[0][3] = nominal.leaves(tight);
  other.join();
  for (int t = 0; t < 2; ++t) {
    EXPECT_EQ(answers[t][0], t == 0 ? tight_leaves : logged_leaves);
    EXPECT_EQ(answers[t][1], t == 0 ? logged_leaves : tight_leaves);
    EXPECT_EQ(answers[t][2], t == 0 ? logged_leaves : tight_leaves);
    EXPECT_EQ(answers[t][3], t == 0 ? tight_leaves : logged_leaves);
  }
  // stabilityRequirements gives the same requirements and note with it as without it.
  const CandidateEffect& column = candidateNamed("steering_compliance", "wheel_sensor");
  CandidateObjective objective = f.objective(column);
  const std::vector<double> unbounded{164265.0, 11.16, 0.0458};
  std::string note_without, note_with;
  const auto without = stabilityRequirements(objective, unbounded, f.data, &note_without);
  const auto with = stabilityRequirements(objective, unbounded, f.data, &note_with, &nominal);
  ASSERT_EQ(without.size(), 1u);
  ASSERT_EQ(with.size(), 1u);
  EXPECT_EQ(with[0].log, without[0].log);
  EXPECT_EQ(with[0].max_steering_angle, without[0].max_steering_angle);
  EXPECT_EQ(note_with, note_without);
  EXPECT_FALSE(note_with.empty());
}

}  // namespace
}  // namespace diagnosis
}  // namespace lane_keeping

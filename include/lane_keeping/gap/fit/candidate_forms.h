#pragma once
/// Effects with several placements (steering_compliance: the actuator's angle sensor at the road wheel or on the motor side;
/// lateral_disturbance: a crosswind the accelerometer senses or a road bank it does not) are fitted in
/// every form. The data choose the form: the one with the smaller training gap after its fit stands for
/// the effect in the ranking and the verdict (held-out data stay for scoring the effect, not for
/// choosing among its forms). The verdict keeps DESIGN §5's effect name; the report names the form.
/// A sensor error's forms are its channels (sensor_offset of the yaw rate, of the heading, ...): errors
/// of different sensors, never compared as forms; each stays in the ranking.
#include <string>
#include <vector>

#include "lane_keeping/gap/fit/candidate_fit.h"

namespace lane_keeping {
namespace diagnosis {

/// Keeps, for each effect, the form whose fit succeeded with the smallest training gap (the first form
/// on a tie, or when none succeeded), and drops the others; a note names the forms compared and their
/// training gaps. The order of the remaining fits is kept.
void keepBestForms(std::vector<CandidateFit>* fits, std::vector<std::string>* notes);

}  // namespace diagnosis
}  // namespace lane_keeping

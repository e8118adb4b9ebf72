#include "lane_keeping/gap/evaluation/loop_ringing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "lane_keeping/common/median.h"
#include "lane_keeping/gap/log/band_noise.h"
#include "lane_keeping/gap/log/linear_resample.h"
#include "lane_keeping/gap/log/time_holes.h"

namespace lane_keeping {

std::optional<LoopRinging> loopRinging(const LogSignals& log, const GapLog& nominal, LogSignals::Channel channel,
                                       const char* column) {
  const std::vector<double>* simulated = nominal.column(column);
  if (!log.has(channel) || simulated == nullptr || simulated->size() != nominal.t.size() || nominal.t.size() < 2) {
    return std::nullopt;
  }
  const double step = log.log().medianStep();
  if (!(step > 0.0)) return std::nullopt;
  const auto stretches = holeFreeStretches(log.times());
  UpperBand logged = upperBand(log.samples(channel), stretches);
  const UpperBand modelled = upperBand(linearAt(nominal.t, *simulated, log.times()), stretches);
  if (logged.mean.empty() || modelled.mean.size() != logged.mean.size()) return std::nullopt;
  // The noise level: the median over the bins of each bin's median over the segments, over ln 2 (band_noise.h);
  // a white bin's mean is that level.
  const double noise = median(logged.median) / std::log(2.0);
  const auto peak = std::max_element(logged.mean.begin(), logged.mean.end());
  if (!(noise > 0.0) || !(*peak >= kRingingProminence * noise)) return std::nullopt;
  // Narrow: the band's middle bin far below the peak.
  if (!(*peak >= kRingingNarrowness * median(logged.mean))) return std::nullopt;
  const std::size_t bin = static_cast<std::size_t>(peak - logged.mean.begin());
  LoopRinging r;
  r.source = log.log().source;
  r.column = column;
  r.rate = 1.0 / step;
  r.bin_width = upperBandFrequency(1, r.rate) - upperBandFrequency(0, r.rate);
  r.frequency = upperBandFrequency(bin, r.rate);
  r.prominence = *peak / noise;
  r.nominal_share = modelled.mean[bin] / *peak;
  if (!(r.nominal_share <= kRingingNominalShare)) return std::nullopt;
  return r;
}

std::string ringingNote(const std::string& source, const LoopRinging& r) {
  char text[640];
  std::snprintf(text, sizeof text,
                "%s: the logged %s rings at %.1f Hz (a narrow peak %.0f times its upper band's noise level; the nominal "
                "closed loop simulated over the log holds %.2g of it there): if this is the steering loop's fast mode, "
                "seen at %.0f Hz as %.1f, %.1f or %.1f Hz, the loop is nearer its stability margin than the nominal's "
                "(a longer actuation or sensing delay, a stiffer gain), which replays stepping between samples %.3g s "
                "apart may not resolve",
                source.c_str(), r.column == "delta" ? "steering angle" : "steering torque", r.frequency, r.prominence,
                r.nominal_share, r.rate, r.frequency, r.rate - r.frequency, r.rate + r.frequency, 1.0 / r.rate);
  return text;
}

}  // namespace lane_keeping

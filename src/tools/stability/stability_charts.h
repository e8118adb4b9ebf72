#pragma once
// lk_stability's chart sub-commands: `chart` (any two numeric keys, optional series and panels) and
// the paper's Figs 3-5. Each writes PREFIX.csv, PREFIX.json and, through scripts/plot_stability.py
// run by Debian's /usr/bin/python3 (it has matplotlib), PREFIX.png.
#include "lane_keeping/config/sim_config.h"
#include "stability_cli.h"

namespace lane_keeping {
namespace stability_cli {

int commandChart(const Args& a, const SimConfig& c);
int commandFig3(const Args& a, SimConfig c);
int commandFig4(const Args& a, SimConfig c);
int commandFig5(const Args& a, SimConfig c);

}  // namespace stability_cli
}  // namespace lane_keeping

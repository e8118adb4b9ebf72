// Configuration: every shipped file loads; default.yaml equals the compiled defaults; bad input gives
// an error naming the key and the file:line; nothing runs on with NaN.
#include <gtest/gtest.h>

#include <cstdio>
#include <dirent.h>
#include <fstream>
#include <sstream>

#include "lane_keeping/config/flat_params.h"
#include "lane_keeping/config/sim_config.h"
#include "build_paths.h"

namespace lane_keeping {
namespace {

const std::string kSource = build_paths::sourceDir();

std::string writeTemp(const std::string& name, const std::string& text) {
  const std::string path = testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

std::string errorOf(const std::vector<std::string>& files, const std::vector<std::string>& sets = {}) {
  try {
    loadSimConfig(files, sets);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

std::vector<std::string> yamlFiles(const std::string& dir) {
  std::vector<std::string> files;
  if (DIR* d = opendir(dir.c_str())) {
    while (dirent* entry = readdir(d)) {
      const std::string name = entry->d_name;
      if (name.size() > 5 && name.substr(name.size() - 5) == ".yaml") files.push_back(dir + "/" + name);
    }
    closedir(d);
  }
  return files;
}

TEST(ConfigFiles, EveryShippedConfigLoadsAndValidates) {
  auto files = yamlFiles(kSource + "/config");
  const auto scenarios = yamlFiles(kSource + "/config/scenarios");
  files.insert(files.end(), scenarios.begin(), scenarios.end());
  const auto vehicles = yamlFiles(kSource + "/config/vehicles");  // with a log: section, which lk_simulate ignores
  files.insert(files.end(), vehicles.begin(), vehicles.end());
  ASSERT_GE(files.size(), 7u);
  for (const auto& file : files) {
    SCOPED_TRACE(file);
    EXPECT_NO_THROW(loadSimConfig({file}));
  }
}

TEST(ConfigFiles, DefaultYamlEqualsCompiledDefaults) {
  std::ostringstream compiled, loaded;
  SimConfig{}.print(compiled);
  loadSimConfig({kSource + "/config/default.yaml"}).print(loaded);
  EXPECT_EQ(compiled.str(), loaded.str());
}

// What a node reads from the parameter server (MissingKeys::kRefuse): default.yaml holds every key,
// so the launch files' tree is complete; a tree missing keys is refused naming each with its default,
// and an overlay alone (what a launch that forgot default.yaml would load) is refused too.
TEST(ConfigErrors, APartialTreeIsRefusedNamingEveryMissingKey) {
  FlatParams complete;
  complete.overlayFile(kSource + "/config/default.yaml");
  complete.overlayFile(kSource + "/config/scenarios/fig6.yaml");
  EXPECT_NO_THROW(simConfigFromFlat(complete, MissingKeys::kRefuse));

  FlatParams partial = complete;
  partial.erasePrefix("delays.pose_to_tracker");
  partial.erasePrefix("vehicle.mass");
  EXPECT_NO_THROW(simConfigFromFlat(partial));  // files: absent keys keep their defaults
  try {
    simConfigFromFlat(partial, MissingKeys::kRefuse);
    FAIL() << "a tree without delays.pose_to_tracker and vehicle.mass was accepted";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("delays.pose_to_tracker is missing (its default would be 0.2 s)"), std::string::npos) << what;
    EXPECT_NE(what.find("vehicle.mass is missing (its default would be"), std::string::npos) << what;
    EXPECT_EQ(what.find("tracker.k_y"), std::string::npos) << what;  // only the missing ones
  }

  FlatParams overlay_only;
  overlay_only.overlayFile(kSource + "/config/scenarios/fig6.yaml");
  try {
    simConfigFromFlat(overlay_only, MissingKeys::kRefuse);
    FAIL() << "a tree holding only an overlay was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("vehicle.wheelbase"), std::string::npos) << e.what();
  }
}

TEST(ConfigErrors, NegativeMassNamesKeyFileAndLine) {
  const std::string file = writeTemp("neg_mass.yaml", "vehicle:\n  wheelbase: 2.57\n  mass: -1100\n");
  const std::string error = errorOf({file});
  EXPECT_NE(error.find("vehicle.mass"), std::string::npos) << error;
  EXPECT_NE(error.find("neg_mass.yaml:3"), std::string::npos) << error;
  EXPECT_NE(error.find("must be > 0 kg"), std::string::npos) << error;
}

TEST(ConfigErrors, ZeroSpeed) {
  const std::string error = errorOf({}, {"vehicle.speed=0"});
  EXPECT_NE(error.find("vehicle.speed"), std::string::npos) << error;
  EXPECT_NE(error.find("--set"), std::string::npos) << error;
}

TEST(ConfigErrors, NanGain) {
  const std::string file = writeTemp("nan_gain.yaml", "tracker:\n  k_y: .nan\n");
  const std::string error = errorOf({file});
  EXPECT_NE(error.find("tracker.k_y"), std::string::npos) << error;
  EXPECT_NE(error.find("nan"), std::string::npos) << error;
  EXPECT_NE(error.find("nan_gain.yaml:2"), std::string::npos) << error;
}

TEST(ConfigErrors, UnknownTireModelListsTheAllowedOnes) {
  const std::string error = errorOf({}, {"tire.rear.model=pacejka2002"});
  EXPECT_NE(error.find("tire.rear.model"), std::string::npos) << error;
  EXPECT_NE(error.find("lugre_lumped"), std::string::npos) << error;
}

TEST(ConfigErrors, MissingFile) {
  const std::string error = errorOf({"/nonexistent/lk.yaml"});
  EXPECT_NE(error.find("/nonexistent/lk.yaml"), std::string::npos) << error;
  EXPECT_NE(error.find("cannot open"), std::string::npos) << error;
}

TEST(ConfigErrors, MalformedYamlNamesLine) {
  const std::string file = writeTemp("broken.yaml", "vehicle:\n  mass: 1100\n  speed: [15\ntracker:\n  k_y: 0.1\n");
  const std::string error = errorOf({file});
  EXPECT_NE(error.find("broken.yaml:"), std::string::npos) << error;
  EXPECT_NE(error.find("malformed YAML"), std::string::npos) << error;
}

// Found by fuzzing (fuzz/regressions/sim_config/complex_key.yaml): a key that is a list or a mapping
// ("? k_y: 0.05" makes the key the mapping {k_y: 0.05}) escaped as yaml-cpp's TypedBadConversion.
TEST(ConfigErrors, AKeyThatIsNotANameNamesFileAndLine) {
  const std::string file = writeTemp("complex_key.yaml", "tracker:\n  k_psi: 0.8\n? k_y: 0.05\n");
  std::string error = errorOf({file});
  EXPECT_NE(error.find("complex_key.yaml:3"), std::string::npos) << error;
  EXPECT_NE(error.find("a key must be a name, found a mapping"), std::string::npos) << error;
  error = errorOf({}, {"tracker={[1]: 2}"});
  EXPECT_NE(error.find("a key must be a name, found a list"), std::string::npos) << error;
  error = errorOf({kSource + "/fuzz/regressions/sim_config/complex_key.yaml"});
  EXPECT_NE(error.find("a key must be a name"), std::string::npos) << error;
}

// A key given twice in one mapping (unique_keys.h; found by the log_mapping fuzz target,
// fuzz/regressions/log_mapping/duplicate_columns_key.yaml): yaml-cpp kept both, and the configuration took
// the second `vehicle:` section's mass without a word.
TEST(ConfigErrors, AKeyGivenTwiceInOneMappingNamesBothLines) {
  const std::string file = writeTemp("twice.yaml", "vehicle:\n  mass: 1000\ntracker:\n  k_y: 0.1\nvehicle:\n  mass: 2000\n");
  std::string error = errorOf({file});
  EXPECT_NE(error.find("twice.yaml:5"), std::string::npos) << error;
  EXPECT_NE(error.find("vehicle is given twice in one mapping (first at line 1)"), std::string::npos) << error;
  // Below the top level, and in a list's mapping.
  error = errorOf({writeTemp("twice_nested.yaml", "tracker:\n  k_y: 0.1\n  k_psi: 0.8\n  k_y: 0.2\n")});
  EXPECT_NE(error.find("tracker.k_y is given twice in one mapping (first at line 2)"), std::string::npos) << error;
  error = errorOf({writeTemp("twice_listed.yaml", "changes:\n  - {t: 1, t: 2}\n")});
  EXPECT_NE(error.find("changes[0].t is given twice"), std::string::npos) << error;
  // The same key in two files (or a file and --set) is an overlay, not a mistake.
  EXPECT_EQ(errorOf({writeTemp("once_a.yaml", "vehicle:\n  mass: 1000\n"), writeTemp("once_b.yaml", "vehicle:\n  mass: 1200\n")},
                    {"vehicle.mass=1300"}),
            "");
}

TEST(ConfigErrors, UnknownKeyAndTypeErrorsAreAllReported) {
  const std::string file = writeTemp("typos.yaml", "tracker:\n  k_yy: 0.1\n  k_psi: fast\nvehicle:\n  mass: 0\n");
  const std::string error = errorOf({file});
  EXPECT_NE(error.find("tracker.k_yy"), std::string::npos) << error;
  EXPECT_NE(error.find("not a known parameter"), std::string::npos) << error;
  EXPECT_NE(error.find("tracker.k_psi"), std::string::npos) << error;
  EXPECT_NE(error.find("typos.yaml:3"), std::string::npos) << error;
}

TEST(ConfigErrors, CrossFieldRules) {
  EXPECT_NE(errorOf({}, {"vehicle.cg_to_rear_axle=3.0"}).find("smaller than vehicle.wheelbase"), std::string::npos);
  EXPECT_NE(errorOf({}, {"tire.front.model=lugre_distributed", "tire.front.lugre.bristles=2000"})
                .find("RK4's stability limit"),
            std::string::npos);
  EXPECT_NE(errorOf({}, {"simulation.step=1.5e-9"}).find("even number of nanoseconds"), std::string::npos);
  // A run whose log or step count no machine holds is refused up front (was std::bad_alloc).
  EXPECT_NE(errorOf({}, {"simulation.duration=1e9"}).find("simulation.duration / simulation.step = 1e+13 plant steps"),
            std::string::npos);
  EXPECT_NE(errorOf({}, {"simulation.log_rate=1e9"}).find("x simulation.log_rate = 1e+10 log rows; at most 2e+07"),
            std::string::npos);
  EXPECT_EQ(errorOf({}, {"simulation.duration=20000", "simulation.log_rate=1000"}), "");  // 2e7 rows: allowed
}

TEST(ConfigErrors, SimulateExitsWithStatus2AndTheMessage) {
  const std::string out = testing::TempDir() + "lk_err.txt";
  const int status = std::system((std::string(build_paths::lkSimulateBinary()) + " --set vehicle.mass=-1 2>" + out + " >/dev/null").c_str());
  EXPECT_EQ(WEXITSTATUS(status), 2);
  std::ifstream in(out);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("vehicle.mass"), std::string::npos) << text.str();
}

TEST(CoreLibrary, HasNoRosInclude) {
  // House rule 1: the core builds and is tested without roscpp.
  const std::string command = "grep -rlE '#include [<\"](ros/|ros\\.h|nodelet|tf2_ros|rosbag)' " + kSource +
                              "/src/core " + kSource + "/include/lane_keeping";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char buffer[512];
  std::string hits;
  while (fgets(buffer, sizeof(buffer), pipe)) hits += buffer;
  pclose(pipe);
  EXPECT_EQ(hits, "") << "ROS includes in the core: " << hits;
}

TEST(ConfigFiles, WaypointsFromACsvFileBesideTheYaml) {
  // A lane from a map: path.waypoints names a CSV file (header and comments skipped), relative to the YAML.
  writeTemp("lane_points.csv", "x,y\n# a comment\n0,0\n50,0.5\n100,2\n");
  const std::string file = writeTemp("lane_from_csv.yaml", "path:\n  type: waypoints\n  waypoints: lane_points.csv\n");
  const SimConfig c = loadSimConfig({file});
  ASSERT_EQ(c.path.waypoints.size(), 3u);
  EXPECT_EQ(c.path.waypoints[1][0], 50.0);
  EXPECT_EQ(c.path.waypoints[2][1], 2.0);
}

TEST(ConfigFiles, AnAliasedValueKeepsItsValueWhenTheOtherKeyIsOverridden) {
  // k_psi is an alias of k_y's node ("*g"). The entries hold the document's nodes without a clone, and
  // yaml-cpp's Node assignment rebinds a node in place: replacing k_y by assignment would change k_psi
  // with it. Replacing by erase and insert (flat_params.cpp) leaves it.
  const std::string file = writeTemp("aliased.yaml", "tracker:\n  k_y: &g 0.125\n  k_psi: *g\n");
  const SimConfig c = loadSimConfig({file}, {"tracker.k_y=0.25"});
  EXPECT_EQ(c.tracker.k_y, 0.25);
  EXPECT_EQ(c.tracker.k_psi, 0.125);
  const SimConfig twice = loadSimConfig({file, writeTemp("override.yaml", "tracker:\n  k_psi: 0.5\n")});
  EXPECT_EQ(twice.tracker.k_y, 0.125);
  EXPECT_EQ(twice.tracker.k_psi, 0.5);
}

TEST(ConfigErrors, ABadLineOfAWaypointsFileNamesTheFileAndLine) {
  writeTemp("bad_points.csv", "x,y\n0,0\n50,oops\n");
  const std::string file = writeTemp("lane_bad.yaml", "path:\n  type: waypoints\n  waypoints: bad_points.csv\n");
  const std::string error = errorOf({file});
  EXPECT_NE(error.find("path.waypoints"), std::string::npos) << error;
  EXPECT_NE(error.find("bad_points.csv:3"), std::string::npos) << error;
  const std::string missing = writeTemp("lane_missing.yaml", "path:\n  type: waypoints\n  waypoints: nowhere.csv\n");
  EXPECT_NE(errorOf({missing}).find("cannot open the points file"), std::string::npos) << errorOf({missing});
}

}  // namespace
}  // namespace lane_keeping

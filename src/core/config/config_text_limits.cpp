#include "lane_keeping/config/config_text_limits.h"

#include <sstream>
#include <vector>

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/exceptions.h>
#include <yaml-cpp/mark.h>
#include <yaml-cpp/parser.h>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/yaml_position.h"

namespace lane_keeping {
namespace {

/// Counts values as yaml-cpp reports them, keeping the dotted key of where it is.
class SizeScan : public YAML::EventHandler {
 public:
  explicit SizeScan(const std::string& origin) : origin_(origin) {}

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { leaf(mark, "~"); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { leaf(mark, "*"); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t, const std::string& value) override {
    leaf(mark, value);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    open(mark, false);
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    open(mark, true);
  }
  void OnMapEnd() override { close(); }

 private:
  struct Frame {
    bool map = false;
    bool wants_key = true;  ///< a map: the next node is a key
    bool is_key = false;    ///< this container is a map's key ("? [a, b]: 1"), not a value
    std::string key;        ///< a map: its current key
    std::size_t values = 0; ///< the outermost list: the values below it
    YAML::Mark mark;
  };

  bool atKey() const { return !stack_.empty() && stack_.back().map && stack_.back().wants_key; }

  void count(const YAML::Mark& mark) {
    if (++total_ > kMaxConfigValues) {
      fail(keyPath(stack_.size()), mark,
           "the configuration holds more than " + std::to_string(kMaxConfigValues) +
               " keys and values (one holds a few hundred): is this the right file? A lane belongs in a CSV "
               "file (path.waypoints: lane.csv)");
    }
    if (outer_list_ >= 0 && ++stack_[static_cast<std::size_t>(outer_list_)].values > kMaxInlineListValues) {
      const Frame& list = stack_[static_cast<std::size_t>(outer_list_)];
      fail(keyPath(static_cast<std::size_t>(outer_list_)), list.mark,
           "holds more than " + std::to_string(kMaxInlineListValues) + " values inline (more than " +
               std::to_string(kMaxInlineListValues / 3) +
               " points [x, y]); a configuration file holds at most that many: put the points in a CSV file "
               "of x,y lines beside it and name the file instead (path.waypoints: lane.csv, "
               "docs/configuration.md)");
    }
  }

  void leaf(const YAML::Mark& mark, const std::string& value) {
    count(mark);
    if (atKey()) {
      stack_.back().key = value;
      stack_.back().wants_key = false;
      return;
    }
    valueDone();
  }

  void open(const YAML::Mark& mark, bool map) {
    count(mark);
    Frame frame;
    frame.map = map;
    frame.mark = mark;
    frame.is_key = atKey();
    if (frame.is_key) stack_.back().wants_key = false;
    stack_.push_back(frame);
    if (!map && outer_list_ < 0) outer_list_ = static_cast<int>(stack_.size()) - 1;
  }

  void close() {
    const bool was_key = stack_.back().is_key;
    stack_.pop_back();
    if (outer_list_ >= static_cast<int>(stack_.size())) outer_list_ = -1;
    if (!was_key) valueDone();
  }

  void valueDone() {
    if (!stack_.empty() && stack_.back().map) stack_.back().wants_key = true;
  }

  /// The dotted key of the maps among the first `depth` frames.
  std::string keyPath(std::size_t depth) const {
    std::string path;
    for (std::size_t i = 0; i < depth && i < stack_.size(); ++i) {
      if (stack_[i].map && !stack_[i].key.empty()) path += (path.empty() ? "" : ".") + stack_[i].key;
    }
    return path;
  }

  [[noreturn]] void fail(const std::string& key, const YAML::Mark& mark, const std::string& message) const {
    throw ConfigError(std::vector<ConfigProblem>{{key, yamlPosition(origin_, mark), message}});
  }

  std::string origin_;
  std::vector<Frame> stack_;
  std::size_t total_ = 0;
  int outer_list_ = -1;
};

}  // namespace

void checkConfigBytes(std::size_t bytes, const std::string& origin) {
  if (bytes > kMaxConfigBytes) {
    throw ConfigError(std::vector<ConfigProblem>{
        {"", origin,
         "holds more than " + std::to_string(kMaxConfigBytes >> 20) + " MB; a configuration file is at most that " +
             "(a lane of many points belongs in a CSV file: path.waypoints: lane.csv)"}});
  }
}

void checkConfigTextSize(const std::string& yaml_text, const std::string& origin) {
  checkConfigBytes(yaml_text.size(), origin);
  if (yaml_text.size() < kConfigScanFromBytes) return;
  // Every value is set off by one of these at least, so their count bounds the values: a text that
  // cannot reach a limit is not scanned (the scan costs as much as yaml-cpp's own; a lane of 10^5 points
  // inline has 4 x 10^5 of them).
  std::size_t separators = 0;
  for (const char c : yaml_text) {
    separators += c == ',' || c == '\n' || c == '[' || c == '{' || c == ':' || c == '-' || c == '?' || c == '*';
  }
  if (separators < kMaxInlineListValues) return;
  std::istringstream in(yaml_text);
  checkConfigStream(in, origin);
}

void checkConfigStream(std::istream& in, const std::string& origin) {
  SizeScan scan(origin);
  try {
    YAML::Parser parser(in);
    while (parser.HandleNextDocument(scan)) {
    }
  } catch (const YAML::Exception&) {
    // Malformed: the parse that follows reports it with its line.
  }
}

}  // namespace lane_keeping

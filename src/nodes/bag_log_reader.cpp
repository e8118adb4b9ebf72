#include "bag_log_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <vector>

#include <boost/make_shared.hpp>
#include <ros/exception.h>
#include <ros/serialization.h>
#include <rosbag/bag.h>
#include <rosbag/exceptions.h>
#include <rosbag/view.h>
#include <std_msgs/Header.h>

#include <lane_keeping/DesiredSteeringArray.h>
#include <lane_keeping/SteeringTorqueArray.h>
#include <lane_keeping/VehicleStateArray.h>

#include "conversions.h"
#include "lane_keeping/common/errors.h"
#include "lane_keeping/gap/log/angle_unwrap.h"
#include "topic_names.h"

namespace lane_keeping {
namespace {

bool endsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// Linear interpolation in a time-sorted (stamp, value) series; false outside it.
bool interpolate(const std::vector<std::pair<Nanoseconds, double>>& series, Nanoseconds t, std::size_t* cursor,
                 double* value) {
  if (series.empty() || t < series.front().first || t > series.back().first) return false;
  std::size_t i = std::min(*cursor, series.size() - 1);
  while (i > 0 && series[i].first > t) --i;
  while (i + 1 < series.size() && series[i + 1].first <= t) ++i;
  *cursor = i;
  if (series[i].first == t || i + 1 == series.size()) {
    *value = series[i].second;
    return true;
  }
  const double w = static_cast<double>(t - series[i].first) / static_cast<double>(series[i + 1].first - series[i].first);
  *value = series[i].second + w * (series[i + 1].second - series[i].second);
  return true;
}

/// rosbag trusts the lengths, counts and offsets a bag states: a corrupt or truncated bag makes it allocate
/// what a length field says (gigabytes) or read records at offsets inside other records. So the records
/// are walked first (bag format 2.0: "#ROSBAG V2.0\n", then records of <header_len><header><data_len><data>,
/// each header a list of <field_len><name>=<value>), and a bag whose records overrun the file, whose index
/// position or chunk positions are not record boundaries, or whose chunks would decompress beyond
/// kMaxChunkBytes is refused naming the byte offset. (rosbag writes 768 kB chunks; 256 MiB is generous.)
class BagStructure {
 public:
  static constexpr std::uint64_t kMaxChunkBytes = 256ull << 20;

  explicit BagStructure(const std::string& path) : path_(path), in_(path, std::ios::binary) {
    if (!in_) return;  // rosbag names the open error
    in_.seekg(0, std::ios::end);
    size_ = static_cast<std::uint64_t>(in_.tellg());
    in_.seekg(0);
    char version[13] = {};
    in_.read(version, sizeof(version));
    if (!in_ || std::memcmp(version, "#ROSBAG V2.0\n", sizeof(version)) != 0) {
      // rosbag would take any first line "#ROS<anything> V2.0" and read records after it.
      fail(0, "the first line is not '#ROSBAG V2.0' (the format rosbag records)");
    }
    std::uint64_t index_pos = 0;
    std::set<std::uint64_t> records, chunks, chunk_positions, connections;
    std::vector<std::pair<std::uint64_t, std::uint64_t>> indexed_connections;  // (index data record, its connection)
    chunk_size_ = 0;  // no chunk yet: an index data record before any chunk indexes nothing
    for (std::uint64_t at = sizeof(version); at < size_;) {
      records.insert(at);
      Fields fields;
      const std::uint64_t data_at = readHeader(at, size_, &fields);
      const std::uint64_t data_len = readLength(data_at, size_, "data");
      const std::uint64_t next = data_at + 4 + data_len;
      const std::string op = fields.count("op") ? fields["op"] : std::string();
      if (op == std::string(1, '\x03')) index_pos = number(fields, "index_pos", at);
      if (op == std::string(1, '\x06')) chunk_positions.insert(number(fields, "chunk_pos", at));
      if (op == std::string(1, '\x05')) {
        chunks.insert(at);
        const std::uint64_t size = number(fields, "size", at);
        if (size > kMaxChunkBytes) fail(at, "a chunk of " + std::to_string(size) + " bytes uncompressed");
        chunk_size_ = size;
        chunk_records_.clear();
        chunk_walked_ = fields["compression"] == "none";
        if (chunk_walked_) {
          if (size != data_len) fail(at, "an uncompressed chunk whose size field differs from its data length");
          for (std::uint64_t inner = data_at + 4; inner < next;) {  // message and connection records
            chunk_records_.insert(inner - (data_at + 4));
            Fields inner_fields;
            const std::uint64_t inner_data = readHeader(inner, next, &inner_fields);
            const std::uint64_t inner_len = readLength(inner_data, next, "data");
            if (inner_fields["op"] == std::string(1, '\x07')) readFields(inner, inner_data + 4, inner_len, &inner_fields);
            inner = inner_data + 4 + inner_len;
          }
        }
      }
      if (op == std::string(1, '\x04')) {
        checkIndexData(at, data_at + 4, data_len, fields);
        indexed_connections.emplace_back(at, number(fields, "conn", at));
      }
      if (op == std::string(1, '\x07')) {
        if (index_pos != 0 && at >= index_pos) connections.insert(number(fields, "conn", at));
        // A connection record's data is a connection header, in the same field format (rosbag parses it).
        readFields(at, data_at + 4, data_len, &fields);
      }
      at = next;
    }
    if (index_pos != 0 && records.count(index_pos) == 0) fail(13, "index position " + std::to_string(index_pos) + " is not a record");
    // rosbag looks up an index data record's connection among the index section's connection records and
    // dereferences what it finds: one that names no connection there (and an entry with an invalid
    // time, which rosbag reports by the connection's topic) was a null pointer read (SEGV in
    // readConnectionIndexRecord200, found by fuzzing).
    for (const auto& [record, connection] : indexed_connections) {
      if (connections.count(connection) == 0) {
        fail(record, "an index of connection " + std::to_string(connection) + ", which the bag's index section does not define");
      }
    }
    for (std::uint64_t chunk : chunk_positions) {
      if (chunks.count(chunk) == 0) fail(13, "chunk position " + std::to_string(chunk) + " is not a chunk");
    }
  }

 private:
  using Fields = std::map<std::string, std::string>;

  [[noreturn]] void fail(std::uint64_t at, const std::string& what) const {
    throw InputError(path_ + ": not a readable bag (corrupt or truncated): byte " + std::to_string(at) + ": " + what);
  }
  std::string bytes(std::uint64_t at, std::uint64_t count) {
    std::string out(count, '\0');
    in_.seekg(static_cast<std::streamoff>(at));
    in_.read(out.data(), static_cast<std::streamsize>(count));
    if (!in_) fail(at, "cannot read " + std::to_string(count) + " bytes");
    return out;
  }
  /// A little-endian uint32 length at `at` whose bytes, and the `count` bytes it announces, end by `end`.
  std::uint64_t readLength(std::uint64_t at, std::uint64_t end, const char* what) {
    if (at + 4 > end) fail(at, std::string("the ") + what + " length runs past the end of its record or file");
    const std::string raw = bytes(at, 4);
    std::uint32_t length = 0;
    std::memcpy(&length, raw.data(), 4);
    if (at + 4 + length > end) {
      fail(at, std::string("a ") + what + " of " + std::to_string(length) + " bytes runs past the end of its record or file");
    }
    return length;
  }
  /// The record header at `at` (its fields into `fields`); returns where the data length is.
  std::uint64_t readHeader(std::uint64_t at, std::uint64_t end, Fields* fields) {
    const std::uint64_t length = readLength(at, end, "header");
    readFields(at, at + 4, length, fields);
    return at + 4 + length;
  }
  /// The `length` bytes at `from` as header fields <field_len><name>=<value> of the record at `at`.
  void readFields(std::uint64_t at, std::uint64_t from, std::uint64_t length, Fields* fields) {
    const std::string header = bytes(from, length);
    for (std::uint64_t f = 0; f < length;) {
      if (f + 4 > length) fail(at, "a header field length runs past its header");
      std::uint32_t field_len = 0;
      std::memcpy(&field_len, header.data() + f, 4);
      if (f + 4 + field_len > length) fail(at, "a header field of " + std::to_string(field_len) + " bytes runs past its header");
      const std::string field = header.substr(f + 4, field_len);
      const std::size_t eq = field.find('=');
      if (eq == std::string::npos) fail(at, "a header field without '='");
      (*fields)[field.substr(0, eq)] = field.substr(eq + 1);
      f += 4 + field_len;
    }
  }
  /// An index data record (op 0x04) lists, for the chunk before it, where each message record starts in
  /// the chunk's uncompressed data: rosbag reads a message's header at that offset with no bounds check (a
  /// bad offset read outside the chunk: SEGV, found by fuzzing in CI). Each offset must lie in the chunk
  /// and, for an uncompressed chunk (walked above), be the start of one of its records; for a compressed
  /// one the record behind it cannot be checked without decompressing, only the bound.
  void checkIndexData(std::uint64_t at, std::uint64_t from, std::uint64_t length, Fields& fields) {
    const std::uint64_t count = number(fields, "count", at);
    if (count * 12 != length) {
      fail(at, "an index of " + std::to_string(count) + " entries in " + std::to_string(length) + " bytes (12 each)");
    }
    const std::string entries = bytes(from, length);
    for (std::uint64_t i = 0; i < count; ++i) {
      // An entry is <sec><nsec><offset>. rosbag builds a ros::Time of the first two, which normalises
      // nsec >= 10^9 into the seconds and throws std::runtime_error when they overflow (found by fuzzing).
      std::uint32_t nsec = 0;
      std::memcpy(&nsec, entries.data() + 12 * i + 4, 4);
      if (nsec >= 1000000000u) {
        fail(at, "index entry " + std::to_string(i) + " has a time of " + std::to_string(nsec) +
                     " ns past its second (at most 999,999,999)");
      }
      std::uint32_t offset = 0;
      std::memcpy(&offset, entries.data() + 12 * i + 8, 4);
      if (offset + 8 > chunk_size_ || (chunk_walked_ && chunk_records_.count(offset) == 0)) {
        fail(at, "index entry " + std::to_string(i) + " points at byte " + std::to_string(offset) +
                     " of its chunk, which is not a record of it (" + std::to_string(chunk_size_) + " bytes)");
      }
    }
  }
  std::uint64_t number(Fields& fields, const std::string& name, std::uint64_t at) const {
    const std::string& value = fields[name];
    if (value.size() != 4 && value.size() != 8) fail(at, "header field '" + name + "' missing or not 4 or 8 bytes");
    std::uint64_t out = 0;
    std::memcpy(&out, value.data(), value.size());
    return out;
  }

  std::string path_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
  // The chunk the next index data records belong to: its uncompressed size and, if it was walked
  // (uncompressed), where its records start in its data.
  std::uint64_t chunk_size_ = 0;
  bool chunk_walked_ = false;
  std::set<std::uint64_t> chunk_records_;
};

/// The message as MessageInstance::instantiate reads it (nullptr if its type differs), but with the sample
/// count checked against the message's size first: roscpp resizes the array to the count the data states
/// before it checks the data holds it (a corrupt count made a 131 GB allocation; found by fuzzing).
template <typename ArrayMsg>
boost::shared_ptr<ArrayMsg> instantiateChecked(const rosbag::MessageInstance& m, const std::string& path) {
  namespace ser = ros::serialization;
  if (m.getMD5Sum() != ros::message_traits::md5sum<ArrayMsg>()) return nullptr;
  std::vector<std::uint8_t> raw(m.size());
  ser::OStream out(raw.data(), static_cast<std::uint32_t>(raw.size()));
  m.write(out);
  ser::IStream in(raw.data(), static_cast<std::uint32_t>(raw.size()));
  std_msgs::Header header;
  std::uint32_t count = 0;
  ser::deserialize(in, header);  // StreamOverrunException if short: readBagLog names the bag
  ser::deserialize(in, count);
  using Sample = typename decltype(ArrayMsg::samples)::value_type;
  const std::uint64_t smallest = ser::serializationLength(Sample());  // a sample with an empty frame_id
  if (count * smallest > in.getLength()) {
    throw InputError(path + ": not a readable bag (corrupt message): a " + m.getTopic() + " message states " +
                     std::to_string(count) + " samples in " + std::to_string(raw.size()) + " bytes");
  }
  auto msg = boost::make_shared<ArrayMsg>();
  ser::IStream whole(raw.data(), static_cast<std::uint32_t>(raw.size()));
  ser::deserialize(whole, *msg);
  return msg;
}

/// The reading proper; rosbag's and roscpp's exceptions pass through it (readBagLog turns them into InputError).
GapLog readSuiteTopics(const std::string& path, double max_rate);

}  // namespace

GapLog readBagLog(const std::string& path, double max_rate) {
  try {
    return readSuiteTopics(path, max_rate);
  } catch (const rosbag::BagException& e) {
    throw InputError(path + ": not a readable bag: " + e.what());
  } catch (const ros::Exception& e) {  // ros::serialization's StreamOverrunException: a message cut short
    throw InputError(path + ": not a readable bag (a message does not match its type): " + e.what());
  } catch (const LaneKeepingError&) {
    throw;
  } catch (const std::runtime_error& e) {
    // ros::Time and ros::Duration throw std::runtime_error ("Time is out of dual 32-bit range") for a time a
    // corrupt bag states that does not fit; anything else is not the bag's fault and goes on.
    if (std::string(e.what()).find("out of dual 32-bit range") == std::string::npos) throw;
    throw InputError(path + ": not a readable bag (a time out of range): " + e.what());
  }
}

namespace {

GapLog readSuiteTopics(const std::string& path, double max_rate) {
  BagStructure{path};  // throws InputError on a bag rosbag would misread
  rosbag::Bag bag;
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    throw InputError(path + ": cannot open bag: " + e.what());
  }
  // Topics of the suite, by suffix (any namespace) and type.
  std::string state_topic, desired_topic, torque_topic;
  std::ostringstream available;
  rosbag::View all(bag);
  for (const rosbag::ConnectionInfo* c : all.getConnections()) {
    available << "\n    " << c->topic << " (" << c->datatype << ")";
    if (endsWith(c->topic, std::string("/") + topics::kVehicleState) && c->datatype == "lane_keeping/VehicleStateArray") {
      state_topic = c->topic;
    }
    if (endsWith(c->topic, std::string("/") + topics::kDesiredSteering) &&
        c->datatype == "lane_keeping/DesiredSteeringArray") {
      desired_topic = c->topic;
    }
    if (endsWith(c->topic, std::string("/") + topics::kSteeringTorque) && c->datatype == "lane_keeping/SteeringTorqueArray") {
      torque_topic = c->topic;
    }
  }
  auto missing = [&](const char* what, const char* type) {
    return InputError(path + ": the bag has no " + what + " topic (lane_keeping/" + type + "); it holds:" + available.str());
  };
  if (state_topic.empty()) throw missing(topics::kVehicleState, "VehicleStateArray");
  if (desired_topic.empty()) throw missing(topics::kDesiredSteering, "DesiredSteeringArray");

  std::vector<std::pair<Nanoseconds, VehicleStateSample>> states;
  std::vector<std::pair<Nanoseconds, double>> desired, torque;
  rosbag::View view(bag, rosbag::TopicQuery(std::vector<std::string>{state_topic, desired_topic, torque_topic}));
  for (const rosbag::MessageInstance& m : view) {
    if (m.getTopic() == state_topic) {
      if (auto msg = instantiateChecked<lane_keeping::VehicleStateArray>(m, path)) {
        for (const auto& s : msg->samples) states.emplace_back(toNanoseconds(s.header.stamp), fromVehicleStateMsg(s));
      }
    } else if (m.getTopic() == desired_topic) {
      if (auto msg = instantiateChecked<lane_keeping::DesiredSteeringArray>(m, path)) {
        for (const auto& s : msg->samples) desired.emplace_back(toNanoseconds(s.header.stamp), s.delta_des);
      }
    } else if (m.getTopic() == torque_topic) {
      if (auto msg = instantiateChecked<lane_keeping::SteeringTorqueArray>(m, path)) {
        for (const auto& s : msg->samples) torque.emplace_back(toNanoseconds(s.header.stamp), s.torque);
      }
    }
  }
  bag.close();
  auto byStamp = [](const auto& a, const auto& b) { return a.first < b.first; };
  std::stable_sort(states.begin(), states.end(), byStamp);
  std::stable_sort(desired.begin(), desired.end(), byStamp);
  std::stable_sort(torque.begin(), torque.end(), byStamp);
  if (states.empty()) throw InputError(path + ": topic " + state_topic + " holds no samples");
  if (desired.empty()) throw InputError(path + ": topic " + desired_topic + " holds no samples");

  GapLog log;
  log.source = path;
  const Nanoseconds period = max_rate > 0.0 ? static_cast<Nanoseconds>(std::llround(1e9 / max_rate)) : 0;
  Nanoseconds last_kept = -1;
  std::size_t desired_cursor = 0, torque_cursor = 0, outside = 0, non_finite = 0;
  for (const auto& [stamp, s] : states) {
    if (last_kept >= 0 && (stamp <= last_kept || stamp - last_kept < period)) continue;
    ++log.rows_read;
    double delta_des = 0.0, command = s.torque;
    const bool have_desired = interpolate(desired, stamp, &desired_cursor, &delta_des);
    const bool have_torque = torque.empty() || interpolate(torque, stamp, &torque_cursor, &command);
    if (!have_desired || !have_torque) {
      ++outside;
      ++log.rows_skipped;
      continue;
    }
    const double values[] = {s.x, s.y, s.psi, s.sigma2, s.delta, s.sigma3, s.speed, s.lateral_acceleration, delta_des, command};
    if (!std::all_of(std::begin(values), std::end(values), [](double v) { return std::isfinite(v); })) {
      ++non_finite;
      ++log.rows_skipped;
      continue;
    }
    last_kept = stamp;
    log.t.push_back(nanosecondsToSeconds(stamp));
    log.x.push_back(s.x);
    log.y.push_back(s.y);
    log.psi.push_back(s.psi);
    log.yaw_rate.push_back(s.sigma2);
    log.delta.push_back(s.delta);
    log.delta_rate.push_back(s.sigma3);
    log.v.push_back(s.speed);
    log.ay.push_back(s.lateral_acceleration);
    log.delta_des.push_back(delta_des);
    log.torque.push_back(command);
  }
  if (torque.empty()) {
    log.notes.push_back("topic " + std::string(topics::kSteeringTorque) +
                        " not recorded: the torque column is the torque acting on the wheel (vehicle_state), which "
                        "equals the command unless delays.torque_to_plant > 0");
  }
  if (outside > 0) log.notes.push_back(std::to_string(outside) + " samples outside the recorded desired steering/torque skipped");
  if (non_finite > 0) log.notes.push_back(std::to_string(non_finite) + " samples holding NaN/Inf skipped");
  if (log.size() < 10) throw InputError(path + ": fewer than 10 usable samples in the bag");
  unwrapHeading(&log);  // a recorder or a localisation may wrap psi at +-pi, as a CSV's can (angle_unwrap.h)
  return log;
}

}  // namespace

}  // namespace lane_keeping

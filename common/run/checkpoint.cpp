#include "common/run/checkpoint.hpp"

#include "common/base/atomic_write.hpp"
#include "common/base/content_hash.hpp"
#include "common/base/errors.hpp"

#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <type_traits>

namespace physarum {
namespace {

constexpr char kMagic[8] = {'P', 'H', 'Y', 'S', 'C', 'K', 'P', 'T'};
constexpr std::size_t kFixedBytes = 40;

// Appends values in native byte order.
class PayloadWriter {
 public:
  template <class T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template <class T>
  void array(const std::vector<T>& values) {
    value(static_cast<std::uint64_t>(values.size()));
    for (const T& v : values) value(v);
  }
  void vectors(const std::vector<Eigen::Vector2d>& values) {
    value(static_cast<std::uint64_t>(values.size()));
    for (const Eigen::Vector2d& v : values) {
      value(v.x());
      value(v.y());
    }
  }
  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

// Reads what PayloadWriter wrote; every read is bounds-checked, so a payload that lies about its
// lengths is an InputError, not a read past the end.
class PayloadReader {
 public:
  PayloadReader(const char* data, std::size_t size, std::string path) : data_(data), size_(size), path_(std::move(path)) {}
  template <class T>
  T value() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, data_ + at_, sizeof v);
    at_ += sizeof v;
    return v;
  }
  template <class T>
  std::vector<T> array() {
    const std::uint64_t n = count(sizeof(T));
    std::vector<T> values(static_cast<std::size_t>(n));
    for (T& v : values) v = value<T>();
    return values;
  }
  std::vector<Eigen::Vector2d> vectors() {
    const std::uint64_t n = count(2 * sizeof(double));
    std::vector<Eigen::Vector2d> values(static_cast<std::size_t>(n));
    for (Eigen::Vector2d& v : values) {
      v.x() = value<double>();
      v.y() = value<double>();
    }
    return values;
  }
  void expect_end() const {
    if (at_ != size_) throw InputError(path_ + ": checkpoint payload has " + std::to_string(size_ - at_) + " bytes left over");
  }

 private:
  std::uint64_t count(std::size_t element_bytes) {
    const auto n = value<std::uint64_t>();
    if (n > (size_ - at_) / element_bytes) throw InputError(path_ + ": checkpoint payload is shorter than the lengths it records");
    return n;
  }
  void need(std::size_t bytes) const {
    if (size_ - at_ < bytes) throw InputError(path_ + ": checkpoint payload ends early");
  }
  const char* data_;
  std::size_t size_;
  std::size_t at_ = 0;
  std::string path_;
};

std::string payload_bytes(const SimulationState& state) {
  PayloadWriter w;
  w.value(static_cast<std::int64_t>(state.steps_taken));
  w.value(state.time);
  const SimulationCounters& c = state.counters;
  for (const long long v : {c.agent_steps, c.face_crossings, c.sensor_face_crossings, c.boundary_hits, c.respawns})
    w.value(static_cast<std::int64_t>(v));
  w.value(static_cast<std::uint64_t>(state.layers.size()));
  for (const IntrinsicVertexData<double>& layer : state.layers)
    w.array(std::vector<double>(layer.begin(), layer.end()));
  const Agents& a = state.agents;
  w.array(a.face);
  w.vectors(a.position);
  w.vectors(a.heading);
  for (const std::vector<double>* v : {&a.age, &a.exposure, &a.exposure_threshold, &a.time_since_decision, &a.accumulated_turn})
    w.array(*v);
  w.value(static_cast<std::uint64_t>(state.model_arrays.size()));
  for (const std::vector<double>& array : state.model_arrays) w.array(array);
  return w.take();
}

SimulationState parse_payload(const char* data, std::size_t size, const std::string& path) {
  PayloadReader r(data, size, path);
  SimulationState state;
  state.steps_taken = r.value<std::int64_t>();
  state.time = r.value<double>();
  SimulationCounters& c = state.counters;
  for (long long* v : {&c.agent_steps, &c.face_crossings, &c.sensor_face_crossings, &c.boundary_hits, &c.respawns})
    *v = r.value<std::int64_t>();
  const auto layers = r.value<std::uint64_t>();
  if (layers > size) throw InputError(path + ": checkpoint payload records " + std::to_string(layers) + " layers");
  for (std::uint64_t i = 0; i < layers; ++i) {
    state.layers.emplace_back(r.array<double>());
  }
  Agents& a = state.agents;
  a.face = r.array<int>();
  a.position = r.vectors();
  a.heading = r.vectors();
  for (std::vector<double>* v : {&a.age, &a.exposure, &a.exposure_threshold, &a.time_since_decision, &a.accumulated_turn})
    *v = r.array<double>();
  const auto arrays = r.value<std::uint64_t>();
  if (arrays > size) throw InputError(path + ": checkpoint payload records " + std::to_string(arrays) + " model arrays");
  for (std::uint64_t i = 0; i < arrays; ++i) state.model_arrays.push_back(r.array<double>());
  r.expect_end();
  return state;
}

template <class T>
void put(std::string& bytes, std::size_t at, T v) {
  std::memcpy(bytes.data() + at, &v, sizeof v);
}
template <class T>
T get(const std::string& bytes, std::size_t at) {
  T v;
  std::memcpy(&v, bytes.data() + at, sizeof v);
  return v;
}

}  // namespace

std::string checkpoint_build_id() { return hex64(executable_hash()); }

std::string checkpoint_bytes(const CheckpointHeader& header, const SimulationState& state) {
  const nlohmann::ordered_json h = {{"build_id", header.build_id}, {"backend", header.backend},
                                    {"device", header.device},     {"scene_hash", header.scene_hash},
                                    {"step", header.step},         {"run", header.run}};
  const std::string header_text = h.dump();
  const std::string payload = payload_bytes(state);
  std::string bytes(kFixedBytes, '\0');
  std::memcpy(bytes.data(), kMagic, sizeof kMagic);
  put<std::uint32_t>(bytes, 8, kCheckpointVersion);
  put<std::uint64_t>(bytes, 16, header_text.size());
  put<std::uint64_t>(bytes, 24, payload.size());
  bytes += header_text;
  bytes += payload;
  put<std::uint64_t>(bytes, 32, content_hash(std::string_view(bytes).substr(kFixedBytes)));
  return bytes;
}

void write_checkpoint(const std::string& path, const CheckpointHeader& header, const SimulationState& state) {
  write_text_file_atomically(path, checkpoint_bytes(header, state));
}

Checkpoint read_checkpoint(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot open the checkpoint");
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  if (file.bad()) throw InputError(path + ": cannot read the checkpoint");
  return parse_checkpoint(bytes, path);
}

Checkpoint parse_checkpoint(const std::string& bytes, const std::string& path) {
  if (bytes.size() < kFixedBytes || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    throw InputError(path + ": not a physarum checkpoint (no PHYSCKPT magic at its start)");
  const auto version = get<std::uint32_t>(bytes, 8);
  if (version != kCheckpointVersion)
    throw InputError(path + ": checkpoint format version " + std::to_string(version) + ", this build reads version " +
                     std::to_string(kCheckpointVersion));
  const auto header_size = get<std::uint64_t>(bytes, 16), payload_size = get<std::uint64_t>(bytes, 24);
  const std::uint64_t body = bytes.size() - kFixedBytes;
  if (header_size > body || payload_size != body - header_size)
    throw InputError(path + ": checkpoint is truncated or padded (" + std::to_string(bytes.size()) + " bytes, its header records " +
                     std::to_string(kFixedBytes + header_size + payload_size) + ")");
  if (content_hash(std::string_view(bytes).substr(kFixedBytes)) != get<std::uint64_t>(bytes, 32))
    throw InputError(path + ": checkpoint is corrupted (its XXH3 checksum does not match its contents); resume from "
                            "another copy or start the run again");
  Checkpoint c;
  try {
    const nlohmann::json h = nlohmann::json::parse(bytes.substr(kFixedBytes, static_cast<std::size_t>(header_size)));
    c.header.build_id = h.at("build_id").get<std::string>();
    c.header.backend = h.at("backend").get<std::string>();
    c.header.device = h.at("device").get<std::string>();
    c.header.scene_hash = h.at("scene_hash").get<std::string>();
    c.header.step = h.at("step").get<long long>();
    c.header.run = h.at("run");
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path + ": checkpoint header is unreadable: " + e.what());
  }
  c.state = parse_payload(bytes.data() + kFixedBytes + header_size, static_cast<std::size_t>(payload_size), path);
  if (c.state.steps_taken != c.header.step)
    throw InputError(path + ": checkpoint header says step " + std::to_string(c.header.step) + ", its state step " +
                     std::to_string(c.state.steps_taken));
  return c;
}

void check_checkpoint_matches(const CheckpointHeader& saved, const CheckpointHeader& resuming, const std::string& path) {
  auto refuse = [&](const std::string& what, const std::string& then, const std::string& now) {
    throw InputError(path + ": the checkpoint is from another " + what + " (" + then + "; this run: " + now +
                     "): resuming would not continue the same run. Resume with the " + what +
                     " that wrote it, or start the run again");
  };
  if (saved.build_id != resuming.build_id) refuse("build of physarum", "build " + saved.build_id, "build " + resuming.build_id);
  if (saved.backend != resuming.backend) refuse("backend", saved.backend, resuming.backend);
  if (saved.device != resuming.device) refuse("device", saved.device, resuming.device);
  if (saved.scene_hash != resuming.scene_hash)
    refuse("scene", "scene hash " + saved.scene_hash, "scene hash " + resuming.scene_hash +
                                                          " — the scene file, its overrides, seed or mesh changed");
}

}  // namespace physarum

#include "opencl/agents.hpp"

#include "common/base/errors.hpp"
#include "opencl/runtime/opencl_error.hpp"

namespace physarum::opencl {
namespace {

template <class T>
std::vector<T> read_all(const ComputeContext& compute, const DeviceBuffer& b, int count) {
  std::vector<T> v(static_cast<size_t>(count));
  if (count > 0) compute.queue.enqueueReadBuffer(b.buffer, CL_TRUE, 0, v.size() * sizeof(T), v.data());
  return v;
}

template <class T>
void write_all(const ComputeContext& compute, const DeviceBuffer& b, const std::vector<T>& v) {
  if (!v.empty()) compute.queue.enqueueWriteBuffer(b.buffer, CL_TRUE, 0, v.size() * sizeof(T), v.data());
}

std::vector<float> to_float(const std::vector<double>& v) { return std::vector<float>(v.begin(), v.end()); }

std::vector<cl_float2> to_float2(const std::vector<Eigen::Vector2d>& v) {
  std::vector<cl_float2> out(v.size());
  for (size_t i = 0; i < v.size(); ++i) out[i] = {{static_cast<float>(v[i].x()), static_cast<float>(v[i].y())}};
  return out;
}

// The domain-order index of the agent a device slot holds (slots are permuted by the face sort):
// an id outside 0..count-1 means the device's state is corrupt.
size_t agent_index(cl_uint id, int count) {
  if (id >= static_cast<cl_uint>(count))
    throw DeviceError("opencl agents: the device returned agent id " + std::to_string(id) + " of " +
                      std::to_string(count));
  return id;
}

}  // namespace

DeviceAgents DeviceAgents::allocate(const ComputeContext& compute, int count) {
  if (count < 0) throw InputError("opencl agents: agent count " + std::to_string(count) + " must be >= 0");
  DeviceAgents a;
  a.count = count;
  const size_t n = static_cast<size_t>(count);
  auto make = [&](const std::string& name, size_t element_bytes) {
    try {
      return allocate_buffer(compute, "agent " + name, n * element_bytes, CL_MEM_READ_WRITE, true);
    } catch (const DeviceError& e) {
      throw DeviceError(std::string(e.what()) + " (for " + std::to_string(count) + " agents)");
    }
  };
  a.face = make("face", sizeof(cl_int));
  a.position = make("position", sizeof(cl_float2));
  a.heading = make("heading", sizeof(cl_float2));
  a.age = make("age", sizeof(cl_float));
  a.exposure = make("exposure", sizeof(cl_float));
  a.exposure_threshold = make("exposure threshold", sizeof(cl_float));
  a.time_since_decision = make("time since decision", sizeof(cl_float));
  a.accumulated_turn = make("accumulated turn", sizeof(cl_float));
  a.id = make("id", sizeof(cl_uint));
  return a;
}

void DeviceAgents::upload(const ComputeContext& compute, const Agents& agents) const {
  if (agents.count() != count)
    throw InputError("opencl agents: upload of " + std::to_string(agents.count()) + " agents into room for " +
                     std::to_string(count));
  std::vector<cl_uint> ids(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) ids[static_cast<size_t>(i)] = static_cast<cl_uint>(i);
  write_all(compute, face, agents.face);
  write_all(compute, position, to_float2(agents.position));
  write_all(compute, heading, to_float2(agents.heading));
  write_all(compute, age, to_float(agents.age));
  write_all(compute, exposure, to_float(agents.exposure));
  write_all(compute, exposure_threshold, to_float(agents.exposure_threshold));
  write_all(compute, time_since_decision, to_float(agents.time_since_decision));
  write_all(compute, accumulated_turn, to_float(agents.accumulated_turn));
  write_all(compute, id, ids);
}

Agents DeviceAgents::download(const ComputeContext& compute) const {
  const std::vector<cl_uint> ids = read_all<cl_uint>(compute, id, count);
  const std::vector<cl_int> f = read_all<cl_int>(compute, face, count);
  const std::vector<cl_float2> p = read_all<cl_float2>(compute, position, count);
  const std::vector<cl_float2> h = read_all<cl_float2>(compute, heading, count);
  const std::vector<float> ag = read_all<float>(compute, age, count);
  const std::vector<float> ex = read_all<float>(compute, exposure, count);
  const std::vector<float> th = read_all<float>(compute, exposure_threshold, count);
  const std::vector<float> ts = read_all<float>(compute, time_since_decision, count);
  const std::vector<float> tu = read_all<float>(compute, accumulated_turn, count);
  Agents out;
  out.resize(count);
  for (size_t i = 0; i < static_cast<size_t>(count); ++i) {
    const size_t a = agent_index(ids[i], count);
    out.face[a] = f[i];
    out.position[a] = {p[i].s[0], p[i].s[1]};
    out.heading[a] = {h[i].s[0], h[i].s[1]};
    out.age[a] = ag[i];
    out.exposure[a] = ex[i];
    out.exposure_threshold[a] = th[i];
    out.time_since_decision[a] = ts[i];
    out.accumulated_turn[a] = tu[i];
  }
  return out;
}

std::vector<int> DeviceAgents::download_faces(const ComputeContext& compute) const {
  const std::vector<cl_uint> ids = read_all<cl_uint>(compute, id, count);
  const std::vector<cl_int> f = read_all<cl_int>(compute, face, count);
  std::vector<int> out(static_cast<size_t>(count));
  for (size_t i = 0; i < f.size(); ++i) out[agent_index(ids[i], count)] = f[i];
  return out;
}

std::vector<const DeviceBuffer*> DeviceAgents::buffers() const {
  return {&face, &position, &heading, &age, &exposure, &exposure_threshold, &time_since_decision, &accumulated_turn, &id};
}

}  // namespace physarum::opencl

#pragma once
// A checkpoint file: a run's whole simulation state (common/simulation/simulation_state.hpp) plus a header
// that says which run it belongs to, so that `physarum run --resume DIR` continues bit for bit or
// refuses with a clear message. Layout (native byte order: a checkpoint is only ever read by the
// build that wrote it, on the machine class it ran on):
//
//   bytes  0..7   magic "PHYSCKPT"
//          8..11  format version (kCheckpointVersion), uint32
//         12..15  zero
//         16..23  header length H in bytes, uint64
//         24..31  payload length P in bytes, uint64
//         32..39  XXH3-64 of the H + P bytes that follow (common/base/content_hash.hpp): a flipped or lost
//                 byte anywhere after the fixed part is detected before anything is restored
//         40..    the header, JSON text: {"build_id", "backend", "device", "scene_hash", "step", "run"}
//         40+H..  the payload: the SimulationState, binary
//
// The file is written under a temporary name and renamed (common/base/atomic_write.hpp): a run killed
// while writing leaves the previous checkpoint intact.
#include "common/simulation/simulation_state.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>

namespace physarum {

constexpr std::uint32_t kCheckpointVersion = 2;  // 2: the model arrays (a growing sheet)

// Which run a state belongs to. A resume refuses a checkpoint whose build, backend, device or scene
// differs from the run resuming it: any of them changes the numbers, so the continuation would not
// be the uninterrupted run's.
struct CheckpointHeader {
  std::string build_id;    // checkpoint_build_id(): the executable's content hash
  std::string backend;     // SimulationBackend::backend_name()
  std::string device;      // SimulationBackend::device_name()
  std::string scene_hash;  // what the run simulates, hashed by the caller (e.g. scene file + overrides + mesh)
  long long step = 0;      // steps taken when the state was saved
  nlohmann::json run = nlohmann::json::object();  // the caller's own bookkeeping (options, rows written so far)
};

struct Checkpoint {
  CheckpointHeader header;
  SimulationState state;
};

// The running program's build: hex64(executable_hash()).
std::string checkpoint_build_id();

// The bytes of a checkpoint file (exposed for tests and for measuring its size).
std::string checkpoint_bytes(const CheckpointHeader& header, const SimulationState& state);
// Writes `path` atomically. InputError naming `path` when it cannot be written.
void write_checkpoint(const std::string& path, const CheckpointHeader& header, const SimulationState& state);

// Reads and verifies `path`: InputError naming the file when it cannot be read, is not a
// checkpoint, is of another format version, is truncated, or its checksum does not match (corrupted).
Checkpoint read_checkpoint(const std::string& path);
// The same checks on a checkpoint's bytes (checkpoint_bytes'), `path` naming them in messages.
Checkpoint parse_checkpoint(const std::string& bytes, const std::string& path);

// Throws InputError naming `path` and the first of build, backend, device and scene that differs
// between the checkpoint (`saved`) and the run that wants to resume from it (`resuming`).
void check_checkpoint_matches(const CheckpointHeader& saved, const CheckpointHeader& resuming, const std::string& path);

}  // namespace physarum

#pragma once
// A sweep's inputs frozen inside its folder, so that the folder can be moved or copied (planned on a
// laptop or a login node, run from a cluster's scratch filesystem) and so that editing the scene after
// planning cannot change the runs silently:
//
//   DIR/inputs/NAME.json    the scene as planned, its file references renamed to the copies below
//   DIR/inputs/files/FILE   a copy of every file the scene or a variant names: the mesh, the images and
//                           vertex fields its maps read, colour-map files
//
// sweep.json lists each frozen file with the XXH3 hash of its bytes (common/base/content_hash.hpp);
// every job checks them before it runs and refuses, naming the file, when one is missing or changed.
// Paths in sweep.json and jobs.jsonl are relative to DIR, and every job runs with DIR as its working
// directory, so nothing in the folder names the place it was planned in.
#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <vector>

namespace physarum::cli {

struct FrozenFile {
  std::string path;    // relative to the sweep folder: "inputs/scene.json", "inputs/files/bunny.obj"
  std::string hash;    // XXH3-64 of its bytes, hex
  std::string source;  // what it was copied from (absolute), for the reader
};

struct FrozenInputs {
  std::string scene;               // the frozen scene, relative to the sweep folder
  std::vector<FrozenFile> files;   // the scene first, then the files it names
  // A string of the scene or of a variant that names a file -> the name of its frozen copy, relative
  // to the frozen scene's folder ("files/bunny.obj"), which is how the frozen scene names it.
  std::map<std::string, std::string> renamed;
  std::string scene_text;  // the frozen scene's bytes (planning only; not part of sweep.json)

  // `value` with every string that names an input replaced by its frozen copy's name.
  nlohmann::ordered_json rename(const nlohmann::ordered_json& value) const;
  nlohmann::ordered_json to_json() const;
  // InputError naming `where` on a malformed "inputs" object.
  static FrozenInputs from_json(const nlohmann::json& j, const std::string& where);
};

// Finds what planning `scene` with these variant values (every value of every --vary or CSV column)
// freezes: a string in the scene or a value that names an existing regular file (relative to the
// scene's folder, as the scene reads it, or absolute) is an input, except the names of the scene's
// own maps and procedural shapes. Reads the files to hash them; copies nothing.
FrozenInputs plan_frozen_inputs(const std::string& scene, const std::vector<nlohmann::json>& values);

// Writes DIR/inputs: the frozen scene and a copy of every file, each to a temporary name first.
void write_frozen_inputs(const FrozenInputs& inputs, const std::string& folder);

// Checks every frozen file against its hash: InputError naming the file when one is missing or its
// bytes changed since planning.
void check_frozen_inputs(const FrozenInputs& inputs, const std::string& folder);

}  // namespace physarum::cli

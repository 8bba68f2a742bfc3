#include "tools/sweep/frozen_inputs.hpp"

#include "common/base/atomic_write.hpp"
#include "common/base/content_hash.hpp"
#include "common/base/errors.hpp"

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace physarum::cli {
namespace {

namespace fs = std::filesystem;

constexpr const char* kInputsFolder = "inputs";

void strings_in(const nlohmann::ordered_json& value, std::vector<std::string>& out) {
  if (value.is_string()) out.push_back(value.get<std::string>());
  if (value.is_structured())
    for (const auto& element : value) strings_in(element, out);
}

// The file `text` names when the scene (in `folder`) reads it as a path; empty when it names none.
std::string named_file(const std::string& text, const fs::path& folder) {
  if (text.empty() || text.rfind("shape:", 0) == 0) return {};
  fs::path path(text);
  if (path.is_relative()) path = folder / path;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return {};
  return fs::absolute(path).lexically_normal().string();
}

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot read the scene file");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// "files/NAME", or "files/STEM-2.EXT", ... when another input already has that name.
std::string frozen_name(const fs::path& source, std::set<std::string>& taken) {
  const std::string stem = source.stem().string(), extension = source.extension().string();
  std::string name = "files/" + source.filename().string();
  for (int k = 2; !taken.insert(name).second; ++k) name = "files/" + stem + "-" + std::to_string(k) + extension;
  return name;
}

}  // namespace

nlohmann::ordered_json FrozenInputs::rename(const nlohmann::ordered_json& value) const {
  if (value.is_string()) {
    const auto it = renamed.find(value.get<std::string>());
    return it == renamed.end() ? value : nlohmann::ordered_json(it->second);
  }
  nlohmann::ordered_json copy = value;
  if (value.is_object()) {
    for (auto it = copy.begin(); it != copy.end(); ++it) it.value() = rename(it.value());
  } else if (value.is_array()) {
    for (auto& element : copy) element = rename(element);
  }
  return copy;
}

nlohmann::ordered_json FrozenInputs::to_json() const {
  nlohmann::ordered_json j;
  j["scene"] = scene;
  j["files"] = nlohmann::ordered_json::array();
  for (const FrozenFile& f : files) j["files"].push_back({{"path", f.path}, {"xxh3", f.hash}, {"source", f.source}});
  j["renamed"] = renamed;
  return j;
}

FrozenInputs FrozenInputs::from_json(const nlohmann::json& j, const std::string& where) {
  try {
    FrozenInputs inputs;
    inputs.scene = j.at("scene").get<std::string>();
    for (const nlohmann::json& f : j.at("files"))
      inputs.files.push_back({f.at("path").get<std::string>(), f.at("xxh3").get<std::string>(), f.at("source").get<std::string>()});
    inputs.renamed = j.at("renamed").get<std::map<std::string, std::string>>();
    return inputs;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(where + ": its \"inputs\" are unreadable: " + e.what());
  }
}

FrozenInputs plan_frozen_inputs(const std::string& scene, const std::vector<nlohmann::json>& values) {
  const fs::path scene_path = fs::absolute(scene).lexically_normal();
  const std::string text = read_bytes(scene_path.string());
  const nlohmann::ordered_json parsed = nlohmann::ordered_json::parse(text, nullptr, false);
  if (parsed.is_discarded()) throw InputError(scene + ": not JSON (a scene file)");
  // A map's name is a string of the scene that is not a path even where a file of that name exists.
  std::set<std::string> map_names;
  if (parsed.contains("maps") && parsed["maps"].is_object())
    for (auto it = parsed["maps"].begin(); it != parsed["maps"].end(); ++it) map_names.insert(it.key());

  std::vector<std::string> strings;
  strings_in(parsed, strings);
  for (const nlohmann::json& v : values) strings_in(nlohmann::ordered_json(v), strings);

  FrozenInputs inputs;
  inputs.scene = (fs::path(kInputsFolder) / scene_path.filename()).string();
  std::map<std::string, std::string> frozen_of_file;  // absolute source -> frozen name
  std::set<std::string> taken;
  std::vector<FrozenFile> files;
  for (const std::string& s : strings) {
    if (map_names.count(s) || inputs.renamed.count(s)) continue;
    const std::string file = named_file(s, scene_path.parent_path());
    if (file.empty()) continue;
    auto [it, fresh] = frozen_of_file.emplace(file, std::string());
    if (fresh) {
      it->second = frozen_name(file, taken);
      files.push_back({(fs::path(kInputsFolder) / it->second).string(), hex64(file_content_hash(file)), file});
    }
    inputs.renamed[s] = it->second;
  }
  // Untouched when it names no file, so the frozen scene reads byte for byte like the planned one.
  inputs.scene_text = inputs.renamed.empty() ? text : inputs.rename(parsed).dump(2) + "\n";
  inputs.files.push_back({inputs.scene, hex64(content_hash(inputs.scene_text)), scene_path.string()});
  inputs.files.insert(inputs.files.end(), files.begin(), files.end());
  return inputs;
}

void write_frozen_inputs(const FrozenInputs& inputs, const std::string& folder) {
  const fs::path dir(folder);
  create_output_folder((dir / kInputsFolder / "files").string());
  write_text_file_atomically((dir / inputs.scene).string(), inputs.scene_text);
  for (const FrozenFile& f : inputs.files) {
    if (f.path == inputs.scene) continue;
    const fs::path target = dir / f.path, partial = dir / (f.path + ".partial");
    std::error_code ec;
    fs::copy_file(f.source, partial, fs::copy_options::overwrite_existing, ec);
    if (!ec) fs::rename(partial, target, ec);
    if (ec) {
      fs::remove(partial, ec);
      throw InputError(f.source + ": cannot copy it into the sweep folder as " + target.string() + ": " + ec.message());
    }
    if (hex64(file_content_hash(target.string())) != f.hash)
      throw InputError(f.source + ": changed while the sweep was being planned; plan it again");
  }
}

void check_frozen_inputs(const FrozenInputs& inputs, const std::string& folder) {
  for (const FrozenFile& f : inputs.files) {
    const fs::path path = fs::path(folder) / f.path;
    if (!fs::is_regular_file(path))
      throw InputError(path.string() + ": missing; it is an input of the sweep, frozen when it was planned (from " +
                       f.source + ")");
    const std::string now = hex64(file_content_hash(path.string()));
    if (now != f.hash)
      throw InputError(path.string() + ": changed since the sweep was planned (XXH3 " + now + ", planned " + f.hash +
                       "); its runs would no longer be the sweep's. Restore the file, or plan a new sweep into "
                       "another folder");
  }
}

}  // namespace physarum::cli

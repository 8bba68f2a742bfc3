#pragma once
// Output files appear whole or not at all: the content is written under a temporary name in the
// same folder and renamed onto the final name (rename is atomic within one file system), so a
// reader — or a crash mid-write — never sees a half-written pheromone.ply or preview.png.
#include <functional>
#include <string>

namespace physarum {

// Calls write(temporary_path); on success renames the temporary file to `path`. When write throws,
// or the rename fails, the temporary file is removed and an InputError names `path` and the cause
// (write's own InputError is passed through). `path`'s folder must exist.
void write_file_atomically(const std::string& path, const std::function<void(const std::string& temporary_path)>& write);

// Convenience: writes `bytes` to `path` atomically (for stats.csv, run.json and the like).
void write_text_file_atomically(const std::string& path, const std::string& bytes);

// Creates the output folder `path` (and its parents) if needed. Throws InputError naming the folder
// (as the --out option that gave it) and the cause when it cannot.
void create_output_folder(const std::string& path);

}  // namespace physarum

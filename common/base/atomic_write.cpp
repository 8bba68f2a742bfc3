#include "common/base/atomic_write.hpp"

#include "common/base/errors.hpp"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <unistd.h>

namespace physarum {

void write_file_atomically(const std::string& path, const std::function<void(const std::string&)>& write) {
  namespace fs = std::filesystem;
  // Unique per process and call, hidden (leading dot), same folder as the target so rename is atomic.
  static std::atomic<unsigned> counter{0};
  const fs::path target(path);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  // Built with append rather than operator+ chains, which trip a GCC 12 -Wrestrict false positive.
  std::string name(1, '.');
  name.append(target.filename().string()).append(".tmp-").append(std::to_string(::getpid()));
  name.append("-").append(std::to_string(counter++));
  const fs::path temporary = folder / name;
  auto discard = [&] {
    std::error_code ignored;
    fs::remove(temporary, ignored);
  };
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) throw InputError(path + ": cannot write: folder " + folder.string() + " does not exist");
  try {
    write(temporary.string());
  } catch (const InputError&) {
    discard();
    throw;
  } catch (const std::exception& e) {
    discard();
    throw InputError(path + ": cannot write: " + e.what());
  }
  if (std::rename(temporary.c_str(), target.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    discard();
    throw InputError(path + ": cannot write (rename from temporary file failed: " + reason + ")");
  }
}

void write_text_file_atomically(const std::string& path, const std::string& bytes) {
  write_file_atomically(path, [&](const std::string& temporary) {
    std::FILE* f = std::fopen(temporary.c_str(), "wb");
    if (!f) throw InputError(path + ": cannot write: " + std::strerror(errno));
    const bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
    const bool closed = std::fclose(f) == 0;
    if (!ok || !closed) throw InputError(path + ": cannot write: " + std::strerror(errno));
  });
}

void create_output_folder(const std::string& path) {
  std::error_code ec;
  std::filesystem::create_directories(path, ec);
  if (ec || !std::filesystem::is_directory(path))
    throw InputError("--out " + path + ": cannot create the output folder (" +
                     (ec ? ec.message() : std::string("a file of that name exists")) + ")");
}

}  // namespace physarum

#include "opencl/runtime/kernel_sources.hpp"

#include "common/base/errors.hpp"
#include "opencl/agent_parameters.hpp"

#include <set>
#include <sstream>

namespace physarum::opencl {
namespace {

// A file of kernels/, or one the host generates from its own tables.
const char* find_file(const std::string& name) {
  for (const EmbeddedFile& f : embedded_kernel_files())
    if (name == f.name) return f.text;
  if (name == "agent_parameters.h") return agent_parameters_header().c_str();
  return nullptr;
}

void append_inlined(const std::string& name, std::set<std::string>& done, std::string& out, int depth) {
  if (depth > 16) throw DeviceError("kernel sources: #include nesting deeper than 16 at " + name);
  if (!done.insert(name).second) return;
  const char* text = find_file(name);
  if (!text) throw DeviceError("kernel sources: kernels/" + name + " is not embedded in this build");
  std::istringstream in(text);
  std::string line;
  int line_number = 0;
  out += "#line 1 \"" + name + "\"\n";
  while (std::getline(in, line)) {
    ++line_number;
    const auto first = line.find_first_not_of(" \t");
    if (first != std::string::npos && line.compare(first, 10, "#include \"") == 0) {
      const auto open = line.find('"', first);
      const auto close = line.find('"', open + 1);
      append_inlined(line.substr(open + 1, close - open - 1), done, out, depth + 1);
      out += "#line " + std::to_string(line_number + 1) + " \"" + name + "\"\n";
      continue;
    }
    out += line;
    out += '\n';
  }
}

}  // namespace

std::string kernel_source(const std::string& name) {
  std::set<std::string> done;
  std::string out;
  append_inlined(name, done, out, 0);
  return out;
}

}  // namespace physarum::opencl

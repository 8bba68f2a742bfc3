#include "common/base/number_format.hpp"

#include <cstdio>

namespace physarum {

std::string format_number(double value) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", value);
  return b;
}

std::string format_bytes(double bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB"};
  int u = 0;
  while (bytes >= 1024.0 && u < 5) bytes /= 1024.0, ++u;
  char b[48];
  std::snprintf(b, sizeof b, "%.3g %s", bytes, units[u]);
  return b;
}

}  // namespace physarum

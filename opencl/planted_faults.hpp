#pragma once
// Deliberate bugs the differential harness plants into the OpenCL kernels to prove it can reject a
// wrong simulation: a harness that cannot fail proves nothing, so `physarum compare --fault NAME`
// must reject each of these. Each is a -D flag that exists only in the build options of a harness
// run: a normal build's kernels never see one.
#include <string>
#include <vector>

namespace physarum::opencl {

struct PlantedFault {
  const char* name;    // as given to --fault
  const char* define;  // the preprocessor symbol the kernels test
  const char* what;    // one line for --help and messages
};

const std::vector<PlantedFault>& planted_faults();

// "-DPHYSARUM_FAULT_..." for a fault name ("" for ""). Throws UsageError listing the known names.
std::string fault_build_option(const std::string& name);

}  // namespace physarum::opencl

#pragma once
// A stopped run to continue (`physarum run --resume DIR`): the checkpoint read from
// DIR/checkpoint.bin, already checked for corruption, and its path for messages. Both models' run
// loops (api/run/run_loop.hpp) restore their backend from it and
// take the run's bookkeeping (stats rows so far, seconds so far) from its header.
#include "common/run/checkpoint.hpp"

#include <string>

namespace physarum {

struct ResumePoint {
  Checkpoint checkpoint;
  std::string path;  // DIR/checkpoint.bin
};

}  // namespace physarum

#pragma once
// The views a finished result is drawn from (`physarum render --views N`): the preview's
// three-quarter view, the three axis views an illustrator asks for, or a turntable.
#include <string>
#include <vector>

namespace physarum {

struct CameraView {
  std::string name;  // used in file names: view_<name>.png
  double azimuth_deg = 35.0;
  double elevation_deg = 25.0;
};

// The three-quarter view preview.png uses.
CameraView preview_view();

// n = 1: the preview view; n = 3: front (+z), side (+x) and top (+y, seen from just below the pole so
// the image's up stays defined); any other n in 2..360: a turntable of n frames around the y axis at
// the preview's elevation, starting at its azimuth. UsageError outside 1..360.
std::vector<CameraView> standard_views(int n);

}  // namespace physarum

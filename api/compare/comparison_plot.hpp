#pragma once
// The picture `physarum compare --out DIR` leaves in DIR/spectra.png: the spectral band powers of
// both backends (mean over seeds, error bars +- one seed-to-seed standard deviation), manifold
// harmonics solid and, on flat domains, the radial FFT bands dashed.
#include <string>
#include <vector>

namespace physarum {

// False, writing nothing, when no band power can be drawn (no band metric, or none finite and > 0 on
// the logarithmic axis): a comparison's verdict never depends on its picture.
bool write_comparison_plot(const std::string& path, const std::vector<std::string>& metric_names,
                           const std::vector<std::vector<double>>& reference,
                           const std::vector<std::vector<double>>& opencl);

}  // namespace physarum

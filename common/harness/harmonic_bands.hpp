#pragma once
// How the harness groups manifold harmonics (eigenpairs of L phi = lambda M phi) into bands whose
// powers it compares between arms. Shared by the agent model's metrics (common/harness/comparison_metrics)
// and the reaction-diffusion ones (common/harness/reaction_diffusion_metrics), which differ only in what
// they call the pattern's scale.
//
// Bands hold equal NUMBERS of consecutive non-constant eigenpairs (not equal widths of
// sqrt(lambda)): on a surface the mode count grows like sqrt(lambda)^2, so equal-width bands put a
// handful of modes in the lowest band, whose power then swings by half its value from seed to seed.
//
// A band holds whole eigenspaces: within a repeated eigenvalue (symmetric shapes have many) the
// solver may return any orthonormal basis, and only the projection onto the WHOLE eigenspace is the
// same from one run to the next. So band edges move up to the next gap in the spectrum, and the top
// cluster is dropped when it reaches the last computed eigenvalue (the solver may have returned only
// part of it).
//
// Only modes at the pattern's scale or finer (lambda >= lambda_pattern) are used: coarser ones see
// only how the pattern happens to be laid out on the surface, which differs from seed to seed by
// more than any affordable number of seeds can average away.
#include <Eigen/Core>

#include <vector>

namespace physarum {

// Fewest modes in one band: a band's power then varies by well under its margin from seed to seed
// (the power of k independent modes has a relative spread of about sqrt(2 / k)).
inline constexpr int kMinModesPerBand = 16;

struct HarmonicBandAssignment {
  std::vector<int> band_of_mode;  // per computed eigenpair: its band, or -1 (constant, too coarse, cut cluster)
  int bands = 0;                  // 0: too few usable modes for one band
  int usable = 0;                 // modes at the pattern's scale or finer, whole eigenspaces
};

// `eigenvalues` ascending (as smallest_eigenpairs returns them); at most `max_bands` bands of at
// least kMinModesPerBand modes each over the usable modes.
HarmonicBandAssignment assign_harmonic_bands(const Eigen::VectorXd& eigenvalues, double lambda_pattern, int max_bands);

}  // namespace physarum

#pragma once
// What `physarum compare --out DIR` shows of the patterns themselves (DIR/fields.png): for each arm,
// the final field of its first seed and the mean of every seed's final field, drawn on the arm's own
// full-resolution mesh from one camera (the input's bounding box: both arms triangulate one input)
// with one colour scale, side by side, so a user sees the two patterns the verdict is about.
#include "common/base/element_data.hpp"

#include <mutex>
#include <string>
#include <vector>

namespace physarum {

struct Arm;

// The final fields of an arm's seeds, as they finish (from several threads).
class SeedFields {
 public:
  void add(int seed_index, const IntrinsicVertexData<double>& field);
  int count() const;
  // Seed index 0's field (empty before it finished) and the mean over every added seed.
  IntrinsicVertexData<double> first() const;
  IntrinsicVertexData<double> mean() const;

 private:
  mutable std::mutex mutex_;
  IntrinsicVertexData<double> first_, sum_;
  int count_ = 0;
};

// Writes the picture described above at `path` (temporary name, then rename). Arms without fields
// are skipped; false, writing nothing, when no arm has any.
bool write_comparison_fields(const std::string& path, const std::vector<Arm>& arms);

}  // namespace physarum

#pragma once
// Independent check of the InputMesh contract (input_mesh.hpp), written without the repair code:
// indices in range, distinct corners, every edge on at most two triangles with opposite
// directions, and every vertex a single fan (its link is one connected path or cycle).
#include "common/mesh/input_mesh.hpp"

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <vector>

namespace physarum::testing {

inline void expect_valid_input_mesh(const InputMesh& m) {
  const int n = m.vertex_count();
  ASSERT_EQ(static_cast<int>(m.file_vertex.size()), n);
  std::map<std::pair<int, int>, int> directed;
  std::vector<std::vector<std::pair<int, int>>> link(n);
  for (const auto& t : m.triangles) {
    for (int k = 0; k < 3; ++k) {
      ASSERT_GE(t[k], 0);
      ASSERT_LT(t[k], n);
    }
    ASSERT_TRUE(t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
    for (int k = 0; k < 3; ++k) {
      ++directed[{t[k], t[(k + 1) % 3]}];
      link[t[k]].push_back({t[(k + 1) % 3], t[(k + 2) % 3]});
    }
  }
  for (const auto& [e, count] : directed) {
    ASSERT_EQ(count, 1) << "directed edge " << e.first << "->" << e.second << " used twice (orientation)";
  }
  std::vector<char> used(n, 0);
  for (int v = 0; v < n; ++v) {
    ASSERT_FALSE(link[v].empty()) << "vertex " << v << " is used by no triangle";
    // Union the link edges; a single fan has a connected link.
    std::map<int, int> parent;
    auto find = [&](int x) {
      if (!parent.count(x)) parent[x] = x;
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    for (const auto& [a, b] : link[v]) parent[find(a)] = find(b);
    std::set<int> roots;
    for (const auto& [a, b] : link[v]) roots.insert(find(a));
    ASSERT_EQ(roots.size(), 1u) << "vertex " << v << " (file vertex " << m.file_vertex[v] << ") has " << roots.size() << " fans";
  }
  if (!m.triangle_uvs.empty()) {
    ASSERT_EQ(m.triangle_uvs.size(), m.triangles.size());
    for (const auto& t : m.triangle_uvs)
      for (int c : t) {
        ASSERT_GE(c, 0);
        ASSERT_LT(c, static_cast<int>(m.uvs.size()));
      }
  }
}

}  // namespace physarum::testing

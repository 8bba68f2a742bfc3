#pragma once
// The agent population of the extended slime-mold model (paper Sec. 3.2, Table 1), stored as a
// structure of arrays (one array per attribute, index = agent id). Both backends hold this state
// (the OpenCL backend in device buffers of the same attributes, opencl/agents.hpp).
//
// An agent lives on one intrinsic face at a time; its position and heading are expressed in that
// face's own 2D frame (surface_domain.hpp). Headings are unit vectors; since every face frame is an
// isometric, counter-clockwise layout, a positive rotation turns the agent to its left.
#include <Eigen/Core>
#include <vector>

namespace physarum {

struct Agents {
  std::vector<int> face;                      // intrinsic face the agent is on
  std::vector<Eigen::Vector2d> position;      // in that face's frame
  std::vector<Eigen::Vector2d> heading;       // unit vector in that face's frame
  std::vector<double> age;                    // a: seconds since the agent (re)spawned
  std::vector<double> exposure;               // lambda: age normalised by the local mean lifetime
  std::vector<double> exposure_threshold;     // lambda_t: the agent turns over once lambda >= lambda_t
  std::vector<double> time_since_decision;    // seconds since the last turn decision (carries the remainder)
  std::vector<double> accumulated_turn;       // radians of turn_rate integrated since the last decision

  int count() const { return static_cast<int>(face.size()); }
  void resize(int n);
  // Appends `other`'s agents after these (populations of competing species, numbered species by
  // species: common/model/species.hpp).
  void append(const Agents& other);
};

// A contiguous run of agent ids [begin, end): one species' agents. The default is every agent.
struct AgentRange {
  int begin = 0;
  int end = 2147483647;
};

// A point on the surface: a face and a position in its frame.
struct FacePoint {
  int face = -1;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
};

}  // namespace physarum

/* Directional bias (paper Sec. 3.3, Fig. 6; mirrors common/directional_bias.cpp and
 * reference/directional_bias.cpp): the heading relaxes toward the CLOSEST of the
 * PHYSARUM_BIAS_SYMMETRY copies of the face's bias direction, d(delta)/dt = -strength delta,
 * integrated exactly over the step, so it never overshoots. Compiled in only when the controls have
 * a bias (PHYSARUM_BIAS): a scene without one pays nothing. */
#ifndef PHYSARUM_BIAS_CL
#define PHYSARUM_BIAS_CL
#include "agents.cl"

/* The signed angle from the closest copy of d to the heading h, in [-pi/n, pi/n]. */
float angle_from_closest_copy(const float2 h, const float2 d) {
  const float period = 2.0f * M_PI_F / (float)PHYSARUM_BIAS_SYMMETRY;
  const float angle = atan2(d.x * h.y - d.y * h.x, d.x * h.x + d.y * h.y);
#ifdef PHYSARUM_FAULT_BIAS_FARTHEST_COPY
  /* planted fault: toward the copy farthest from the heading (the one nearest its opposite) */
  const float opposite = angle - M_PI_F;
  const float from_copy = opposite - period * rint(opposite / period);
  const float to_farthest = from_copy + M_PI_F;
  return to_farthest - 2.0f * M_PI_F * rint(to_farthest / (2.0f * M_PI_F));
#else
  return angle - period * rint(angle / period);
#endif
}

/* The fraction 1 - exp(-x) of the angle a step of the bias turns (x = strength dt >= 0), what the
 * reference computes as -expm1(-x). Not expm1 itself: on PoCL it cost as much as the whole rest of
 * the agent step (bench/README.md, the controls row); exp is cheap. Below x = 1/32 the series
 * (relative error under x^4 / 120 < 1e-8) keeps the small fractions accurate, where 1 - exp(-x) in
 * float would lose digits; above it 1 - exp(-x) is within 2e-6 relative. */
float relaxed_fraction(const float x) {
  if (x < 0.03125f) return x * (1.0f - x * (0.5f - x * (1.0f / 6.0f - x * (1.0f / 24.0f))));
  return 1.0f - exp(-x);
}

/* The heading after one step of the bias at (face, p). */
float2 biased_heading(__global const PhysarumFaceRecord* faces, __global const float2* bias_direction,
                      __global const float* bias_strength, const int face, const float2 p, const float2 heading,
                      const float dt) {
  const float2 d = bias_direction[face];
  const float3 b = barycentric_in_face(faces, face, p);
  const float strength = b.x * bias_strength[faces[face].vertex[0]] + b.y * bias_strength[faces[face].vertex[1]] +
                         b.z * bias_strength[faces[face].vertex[2]];
  if (!(strength > 0.0f) || (d.x == 0.0f && d.y == 0.0f)) return heading;
  const float turn = -angle_from_closest_copy(heading, d) * relaxed_fraction(strength * dt);
  float c;
  const float s = sincos(turn, &c);
  return normalize((float2)(c * heading.x - s * heading.y, s * heading.x + c * heading.y));
}

#endif /* PHYSARUM_BIAS_CL */

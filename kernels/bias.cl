/* Directional bias (paper Sec. 3.3, Fig. 6; mirrors common/model/directional_bias.cpp and
 * reference/directional_bias.cpp): the heading relaxes toward the CLOSEST of the
 * PHYSARUM_BIAS_SYMMETRY copies of the face's bias direction, d(delta)/dt = -strength delta,
 * integrated exactly over the step, so it never overshoots. Compiled in only when the controls have
 * a bias (PHYSARUM_BIAS): a scene without one pays nothing. */
#ifndef PHYSARUM_BIAS_CL
#define PHYSARUM_BIAS_CL
#include "agents.cl"

/* atan2 and sincos by polynomials: PoCL's built-in atan2, sincos and expm1 each cost about a fifth
 * of the whole agent step (bench/README.md, the controls row), these a few multiplications, and both
 * are below float rounding: atan on [0, 1] by Abramowitz & Stegun 4.4.49 (|error| < 2e-8), sine and
 * cosine of theta / 2 (|theta| <= pi) by their Taylor series to degree 13 and 14 (< 2e-9), then the
 * double-angle formulas. */
float bias_atan2(const float y, const float x) {
  const float ax = fabs(x), ay = fabs(y);
  const float big = fmax(ax, ay);
  const float r = big > 0.0f ? fmin(ax, ay) / big : 0.0f;
  const float r2 = r * r;
  float a = 0.0028662257f;
  a = a * r2 - 0.0161657367f;
  a = a * r2 + 0.0429096138f;
  a = a * r2 - 0.0752896400f;
  a = a * r2 + 0.1065626393f;
  a = a * r2 - 0.1420889944f;
  a = a * r2 + 0.1999355085f;
  a = a * r2 - 0.3333314528f;
  a = (a * r2 + 1.0f) * r;
  if (ay > ax) a = 0.5f * M_PI_F - a;
  if (x < 0.0f) a = M_PI_F - a;
  return y < 0.0f ? -a : a;
}

/* sin and cos of theta, |theta| <= pi. */
float2 bias_cos_sin(const float theta) {
  const float h = 0.5f * theta, h2 = h * h;
  const float s =
      h * (1.0f + h2 * (-1.0f / 6.0f + h2 * (1.0f / 120.0f + h2 * (-1.0f / 5040.0f + h2 * (1.0f / 362880.0f +
                                                                                         h2 * (-1.0f / 39916800.0f + h2 * (1.0f / 6227020800.0f)))))));
  const float c =
      1.0f + h2 * (-0.5f + h2 * (1.0f / 24.0f + h2 * (-1.0f / 720.0f + h2 * (1.0f / 40320.0f + h2 * (-1.0f / 3628800.0f +
                                                                                                  h2 * (1.0f / 479001600.0f))))));
  return (float2)(c * c - s * s, 2.0f * s * c);
}

/* The signed angle from the closest copy of d to the heading h, in [-pi/n, pi/n]. */
float angle_from_closest_copy(const float2 h, const float2 d) {
  const float period = 2.0f * M_PI_F / (float)PHYSARUM_BIAS_SYMMETRY;
  const float angle = bias_atan2(d.x * h.y - d.y * h.x, d.x * h.x + d.y * h.y);
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

/* The heading turned by `fraction` of its angle to the closest copy of direction d (none when d is
 * zero). The rotation keeps the length; the division only stops float drift. */
float2 heading_relaxed_toward(const float2 d, const float fraction, const float2 heading) {
  if (!(fraction > 0.0f) || (d.x == 0.0f && d.y == 0.0f)) return heading;
  const float2 r = bias_cos_sin(-angle_from_closest_copy(heading, d) * fraction);
  const float2 turned = (float2)(r.x * heading.x - r.y * heading.y, r.y * heading.x + r.x * heading.y);
  return turned / sqrt(dot(turned, turned));
}

/* The heading after one step of a bias whose strength varies: interpolated at (face, p). With one
 * strength everywhere (PHYSARUM_BIAS_UNIFORM_STRENGTH) the kernel computes the fraction once. */
float2 biased_heading(__global const PhysarumFaceRecord* faces, __global const float2* bias_direction,
                      __global const float* bias_strength, const int face, const float2 p, const float2 heading,
                      const float dt) {
  const float3 b = barycentric_in_face(faces, face, p);
  const float strength = b.x * bias_strength[faces[face].vertex[0]] + b.y * bias_strength[faces[face].vertex[1]] +
                         b.z * bias_strength[faces[face].vertex[2]];
  return heading_relaxed_toward(bias_direction[face], strength > 0.0f ? relaxed_fraction(strength * dt) : 0.0f,
                                heading);
}

#endif /* PHYSARUM_BIAS_CL */

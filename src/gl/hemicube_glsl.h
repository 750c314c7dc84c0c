// GLSL shared by the passes that render hemicubes on the GPU and the passes that look into them,
// so that a point is projected into a hemicube by the same arithmetic that rasterised it. The
// conventions are those of ItemHemicube (hemicube.cpp) on the CPU side: the frame round the normal,
// the five view directions {n, t, -t, b, -b}, glm::lookAt and a 90-degree glm::perspective.
#pragma once

namespace luxel::gl {

inline constexpr const char* kHemicubeGlsl = R"(
struct HemicubeFrame { vec3 n, t, b; };

// Turned by `angle` about the normal: seed 001 turns gathering hemicubes at random so that the
// pixel grid's aliasing of small bright sources becomes noise that the k x k hemicubes average.
HemicubeFrame hemicubeFrame(vec3 n, float angle) {
  vec3 t = normalize(abs(n.x) > 0.9 ? cross(n, vec3(0.0, 1.0, 0.0)) : cross(n, vec3(1.0, 0.0, 0.0)));
  vec3 b = cross(n, t);
  t = cos(angle) * t + sin(angle) * b;
  return HemicubeFrame(n, t, cross(n, t));
}

// An angle in [0, pi/2) hashed from three integers (a patch or element, a hemicube of it, a pass):
// the same every run. gather_gl.cpp's hemicubeTurn computes the same hash in C++.
float hemicubeTurn(uint a, uint b, uint c) {
  uint h = (a * 0x9E3779B1u) ^ (b * 0x85EBCA77u) ^ (c * 0xC2B2AE3Du);
  h ^= h >> 15; h *= 0x2C1B3C6Du; h ^= h >> 12;
  return float(h >> 8) / 16777216.0 * 1.5707963;
}

// The face (0 the top, 1..4 the sides t, -t, b, -b) that direction r from the centre falls on.
int hemicubeFace(vec3 r, HemicubeFrame f) {
  float z = dot(r, f.n), x = dot(r, f.t), y = dot(r, f.b);
  if (z >= abs(x) && z >= abs(y)) return 0;
  if (abs(x) >= abs(y)) return x > 0.0 ? 1 : 2;
  return y > 0.0 ? 3 : 4;
}

// Clip coordinates of world point w on face `face` of the hemicube centred at `eye`: lookAt
// (rows s, u, -d) then a 90-degree perspective with aspect 1, written out.
vec4 hemicubeClip(vec3 w, vec3 eye, HemicubeFrame f, int face, float near, float far) {
  vec3 d, up;
  if (face == 0) { d = f.n; up = f.b; }
  else { up = f.n; d = face == 1 ? f.t : face == 2 ? -f.t : face == 3 ? f.b : -f.b; }
  vec3 s = normalize(cross(d, up));
  vec3 u = cross(s, d);
  vec3 r = w - eye;
  float zv = -dot(d, r);
  return vec4(dot(s, r), dot(u, r), (-(far + near) * zv - 2.0 * far * near) / (far - near), -zv);
}

// The pixel of hemicube `hemicube` (its layers 5 hemicube .. 5 hemicube + 4; centre eye, frame f,
// `resolution` pixels a side) that world point w falls on: the one nearest the projection. z < 0
// when w lies behind every face's plane.
ivec3 hemicubePixelAt(vec3 w, vec3 eye, HemicubeFrame f, float near, float far, int resolution, int hemicube) {
  const int face = hemicubeFace(w - eye, f);
  const vec4 c = hemicubeClip(w, eye, f, face, near, far);
  if (!(c.w > 0.0)) return ivec3(-1);
  const vec2 pixel = (c.xy / c.w * 0.5 + 0.5) * float(resolution);
  return ivec3(clamp(ivec2(floor(pixel)), ivec2(0), ivec2(resolution - 1)), hemicube * 5 + face);
}

// Pixel k of those a hemicube integrates, the top face's then the upper halves of the four
// sides': its face, column x, row y and index d into the delta form factors (top table, then
// the side table, row 0 at the base of the upper half).
void hemicubePixel(int k, int resolution, out int face, out int x, out int y, out int d) {
  const int half_ = resolution / 2, top = resolution * resolution, side = resolution * half_;
  if (k < top) {
    face = 0; x = k % resolution; y = k / resolution; d = k;
  } else {
    const int j = k - top, r = j % side;
    face = 1 + j / side; x = r % resolution; y = half_ + r / resolution; d = top + r;
  }
}

// The direction through the centre of pixel (x, y) of face `face`: hemicubeClip's conventions
// inverted, fwd + x s + y u (not unit).
vec3 hemicubePixelDirection(HemicubeFrame f, int face, int x, int y, int resolution) {
  vec3 fwd, up;
  if (face == 0) { fwd = f.n; up = f.b; }
  else { up = f.n; fwd = face == 1 ? f.t : face == 2 ? -f.t : face == 3 ? f.b : -f.b; }
  const vec3 s = normalize(cross(fwd, up)), u = cross(s, fwd);
  const vec2 ndc = (vec2(x, y) + 0.5) / float(resolution) * 2.0 - 1.0;
  return fwd + ndc.x * s + ndc.y * u;
}
)";

// A compute pass's sum over its work group (GATHER_GROUP threads) of every thread's value, in a
// fixed order: the same answer every run.
inline constexpr const char* kGroupSumGlsl = R"(
shared vec3 partial[GATHER_GROUP];
vec3 groupSum(vec3 value, uint tid) {
  barrier();
  partial[tid] = value;
  barrier();
  for (uint w = GATHER_GROUP / 2; w > 0u; w >>= 1) {
    if (tid < w) partial[tid] += partial[tid + w];
    barrier();
  }
  return partial[0];
}
)";

// The exact point-to-polygon form factor (Lambert's contour integral, as
// transport/form_factor.cpp computes it on the CPU), with the polygon clipped to the receiver's
// upper hemisphere, and the one-sided source test. Corners in vec4 .xyz; `count` 3 or 4.
inline constexpr const char* kFormFactorGlsl = R"(
float edgeTerm(vec3 a, vec3 b, vec3 n) {
  vec3 c = cross(a, b);
  float cl = length(c);
  if (cl <= 0.0) return 0.0;
  return atan(cl, dot(a, b)) * dot(n, c) / cl;
}

float pointToPolygonFormFactor(vec3 p, vec3 n, vec4 corners[4], int count, vec3 polyNormal) {
  if (dot(polyNormal, corners[0].xyz - p) >= 0.0) return 0.0;  // behind a one-sided source
  float d[4];
  bool above = true, below = true;
  for (int i = 0; i < count; ++i) {
    d[i] = dot(n, corners[i].xyz - p);
    above = above && d[i] >= 0.0;
    below = below && d[i] <= 0.0;
  }
  if (below) return 0.0;
  vec3 r[5];
  int m = 0;
  for (int i = 0; i < count; ++i) {
    int j = i + 1 == count ? 0 : i + 1;
    if (above || d[i] > 0.0) r[m++] = corners[i].xyz - p;
    if (!above && (d[i] > 0.0) != (d[j] > 0.0))
      r[m++] = mix(corners[i].xyz, corners[j].xyz, d[i] / (d[i] - d[j])) - p;
  }
  if (m < 3) return 0.0;
  float sum = 0.0;
  for (int i = 0; i < m; ++i) sum += edgeTerm(r[i], r[i + 1 == m ? 0 : i + 1], n);
  return abs(sum) * 0.15915494309189535;  // 1 / (2 pi)
}

// A point on the polygon from (s, t) in [0,1)^2: bilinear on quads, folded barycentric on
// triangles (polygonPoint in transport/form_factor.h).
vec3 polygonPoint(vec4 corners[4], int count, float s, float t) {
  if (count == 3) {
    if (s + t > 1.0) { s = 1.0 - s; t = 1.0 - t; }
    return corners[0].xyz + s * (corners[1].xyz - corners[0].xyz) + t * (corners[2].xyz - corners[0].xyz);
  }
  return mix(mix(corners[0].xyz, corners[1].xyz, s), mix(corners[3].xyz, corners[2].xyz, s), t);
}
)";

}  // namespace luxel::gl

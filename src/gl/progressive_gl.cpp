#include "gl/progressive_gl.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

#include <fmt/format.h>

#include "gl/cross_redistribution_gl.h"
#include "gl/gl_context.h"
#include "gl/gpu_system.h"
#include "gl/gpu_timeline.h"
#include "gl/hemicube_glsl.h"
#include "gl/shader_program.h"
#include "gl/shared_layout.h"
#include "gl/layered_hemicubes.h"
#include "core/spherical_harmonics.h"
#include "core/stopwatch.h"
#include "solve/step_control.h"
#include "luxel/error.h"

namespace luxel::gl {
namespace {


// The buffers as each pass declares them (std430; layouts in shared_layout.h).
const char* kBuffersGlsl = R"(
layout(std430, binding = ELEMENT_BINDING) readonly buffer Elements { GpuElement elements[]; };
layout(std430, binding = PATCH_BINDING) readonly buffer Patches { GpuPatch patches[]; };
layout(std430, binding = PATCH_ELEMENT_BINDING) readonly buffer PatchElements { uint patchElements[]; };
layout(std430, binding = PATCH_STATE_BINDING) buffer PatchStates { GpuPatchState patchStates[]; };
layout(std430, binding = SHOOTER_BINDING) buffer Shooters { GpuShooter shooters[]; };
layout(std430, binding = SOLVER_STATE_BINDING) buffer SolverState {
  float unshotPower; uint chosen; uint shots; uint passes; uint chosenPatch[MAX_SHOOTERS_PER_PASS];
} state;
layout(std430, binding = ELEMENT_STATE_BINDING) buffer ElementStates { GpuElementState states[]; };
)";

// 1. Unshot power per patch: one thread per patch over its elements, summed per channel.
const char* kPowerCompute = R"(
layout(local_size_x = POWER_GROUP) in;
uniform uint patchCount;
void main() {
  uint p = gl_GlobalInvocationID.x;
  if (p >= patchCount) return;
  uvec4 ids = patches[p].ids;
  vec3 sum = vec3(0.0);
  for (uint i = ids.x; i < ids.x + ids.y; ++i) {
    uint e = patchElements[i];
    sum += elements[e].normalArea.w * states[e].unshot.rgb;
  }
  // Its magnitude: after a redistribution the unshot radiosity can be negative ("negative
  // light", which must be shot as well).
  patchStates[p].power = abs(sum.r) + abs(sum.g) + abs(sum.b);
}
)";

// 2. The shooters of this pass, chosen by one work group: the total unshot power (the stopping
// test), then `batch` rounds of arg-max over the patches not yet chosen (ties to the lower index,
// so the choice is deterministic), then one GpuShooter per hemicube. With `emittersOnly`, only
// emitting patches that have not shot yet are candidates.
const char* kSelectCompute = R"(
layout(local_size_x = SELECT_GROUP) in;
uniform uint patchCount, batch, shotLimit, samplesPerSide;
uniform bool emittersOnly;
// A patch's hemicubes turned the same at every shot (followChanges), so that the factors they
// measure are a function of the geometry alone and a redistribution cancels them exactly.
uniform bool fixedTurns;
float candidatePower(uint p) {
  if (emittersOnly && (patchStates[p].shot != 0u || dot(patches[p].emission.rgb, vec3(1.0)) <= 0.0)) return 0.0;
  return patchStates[p].power;
}
uniform float stopPower, offset;
shared float sValue[SELECT_GROUP];
shared uint sIndex[SELECT_GROUP];
shared uint sChosen[MAX_SHOOTERS_PER_PASS];
shared vec3 sUnshot[MAX_SHOOTERS_PER_PASS];
void main() {
  const uint tid = gl_LocalInvocationIndex;
  float sum = 0.0;
  for (uint p = tid; p < patchCount; p += SELECT_GROUP) sum += patchStates[p].power;
  sValue[tid] = sum;
  barrier();
  for (uint w = SELECT_GROUP / 2; w > 0u; w >>= 1) {
    if (tid < w) sValue[tid] += sValue[tid + w];
    barrier();
  }
  const float total = sValue[0];
  const uint shotsBefore = state.shots;
  barrier();
  const uint limit = total > stopPower ? min(batch, shotLimit - min(shotLimit, shotsBefore)) : 0u;
  uint chosen = 0u;
  for (uint k = 0u; k < limit; ++k) {
    float best = 0.0;
    uint bestIndex = 0xFFFFFFFFu;
    for (uint p = tid; p < patchCount; p += SELECT_GROUP) {
      float v = candidatePower(p);
      if (v <= best) continue;
      bool taken = false;
      for (uint j = 0u; j < k; ++j) taken = taken || sChosen[j] == p;
      if (!taken) { best = v; bestIndex = p; }
    }
    sValue[tid] = best;
    sIndex[tid] = bestIndex;
    barrier();
    for (uint w = SELECT_GROUP / 2; w > 0u; w >>= 1) {
      if (tid < w) {
        float v = sValue[tid + w];
        uint i = sIndex[tid + w];
        if (v > sValue[tid] || (v == sValue[tid] && i < sIndex[tid])) { sValue[tid] = v; sIndex[tid] = i; }
      }
      barrier();
    }
    const bool found = sValue[0] > 0.0;
    if (found && tid == 0u) sChosen[k] = sIndex[0];
    barrier();
    if (!found) break;
    chosen = k + 1u;
  }
  // Each chosen patch shoots its area-weighted mean unshot radiosity.
  if (tid < chosen) {
    GpuPatch P = patches[sChosen[tid]];
    vec3 u = vec3(0.0);
    for (uint i = P.ids.x; i < P.ids.x + P.ids.y; ++i) {
      uint e = patchElements[i];
      u += elements[e].normalArea.w * states[e].unshot.rgb;
    }
    sUnshot[tid] = P.normalArea.w > 0.0 ? u / P.normalArea.w : vec3(0.0);
  }
  barrier();
  const uint samples = samplesPerSide * samplesPerSide;
  for (uint r = tid; r < batch * samples; r += SELECT_GROUP) {
    const uint k = r / samples, j = r % samples;
    GpuShooter s;
    s.eye = vec4(0.0); s.normal = vec4(0.0, 0.0, 1.0, 0.0); s.unshot = vec4(0.0); s.emission = vec4(0.0);
    s.ids = uvec4(0u);
    if (k < chosen) {
      const uint p = sChosen[k];
      GpuPatch P = patches[p];
      const float ks = float(samplesPerSide);
      vec3 x = polygonPoint(P.corners, int(P.corners[0].w), (float(j % samplesPerSide) + 0.5) / ks,
                            (float(j / samplesPerSide) + 0.5) / ks);
      s.eye = vec4(x + offset * P.normalArea.xyz, 0.0);
      // Turned about the normal by a hashed angle (001's random rotation): with the scene's edges
      // and the pixel grid aligned, aliasing at an opening repeated in every hemicube and left
      // the room of the indirect-light scene 10-15% dark at 64 pixels; turned, it averages out.
      s.normal = vec4(P.normalArea.xyz, hemicubeTurn(p, j, fixedTurns ? 0x5EEDu : shotsBefore));
      s.unshot = vec4(sUnshot[k], 0.0);
      s.emission = vec4(patchStates[p].shot == 0u ? P.emission.rgb : vec3(0.0), 0.0);
      s.ids = uvec4(p, 1u, 0u, 0u);
    }
    shooters[r] = s;
  }
  memoryBarrierBuffer();
  barrier();  // every shot flag read before any is set
  if (tid < chosen) patchStates[sChosen[tid]].shot = 1u;
  if (tid == 0u) {
    state.unshotPower = total;
    state.chosen = chosen;
    state.shots = shotsBefore + chosen;
    state.passes += 1u;
    for (uint k = 0u; k < chosen; ++k) state.chosenPatch[k] = sChosen[k];
  }
}
)";

// 4. Reconstruction: one thread per element gathers the pass's shots ("gathered writes", 001
// section 4.3.1), so no two threads write one element.
const char* kReconstructCompute = R"(
layout(local_size_x = RECONSTRUCT_GROUP) in;
layout(binding = ITEM_TEXTURE_UNIT) uniform usampler2DArray items;
layout(binding = DISTANCE_TEXTURE_UNIT) uniform sampler2DArray distances;
layout(std430, binding = FACE_NEIGHBOUR_BINDING) readonly buffer FaceNeighbours { uint faceNeighbours[]; };
uniform uint elementCount, samples;
uniform int resolution, visibility;  // visibility 0: item ids, 1: distances
uniform bool redistributing;         // shots that move light already shot: no shooter's unshot is spent
// Cross-redistribution (cross_redistribution_gl.h): the pass's shooters are moved patches, and a
// static receiver also gains F (-crossSign) P, the light of the static patches behind them.
uniform bool crossProjecting;
uniform float crossSign;
uniform uint crossPatchCount;  // crossBehind holds each patch's view behind the pass's movers (0: not kept)
uniform float nearPlane, farPlane;
// Directional bakes (Solver::recordIncidentSh): the SH of what each shot brings, shCount (4: L1,
// 9: L2; 0: not recording) per element.
layout(std430, binding = ELEMENT_SH_BINDING) buffer ElementSh { vec4 elementSh[]; };
uniform int shCount;

// The moments of polygon q (count corners) seen from x, clipped to the half-space in front of x's
// plane (normal n): its irradiance vector per unit exitance (Arvo 1994's contour sum) and its solid
// angle (Van Oosterom and Strackee 1983, a fan of triangles). transport/form_factor.h's
// clippedPolygonMoments.
void clippedMoments(vec3 x, vec3 n, vec3 q[4], int count, out vec3 v, out float omega) {
  v = vec3(0.0);
  omega = 0.0;
  float d[4];
  bool above = true;
  for (int i = 0; i < count; ++i) {
    d[i] = dot(n, q[i] - x);
    above = above && d[i] >= 0.0;
  }
  vec3 r[5];
  int m = 0;
  for (int i = 0; i < count; ++i) {
    int j = i + 1 == count ? 0 : i + 1;
    if (above || d[i] > 0.0) r[m++] = q[i] - x;
    if (!above && (d[i] > 0.0) != (d[j] > 0.0)) r[m++] = mix(q[i], q[j], d[i] / (d[i] - d[j])) - x;
  }
  for (int i = 0; m >= 3 && i < m; ++i) {
    const vec3 e = cross(r[i], r[i + 1 == m ? 0 : i + 1]);
    const float el = length(e);
    if (el > 0.0) v += atan(el, dot(r[i], r[i + 1 == m ? 0 : i + 1])) / el * e;
  }
  v *= (dot(v, n) < 0.0 ? -1.0 : 1.0) * 0.15915494309189535;
  for (int i = 1; i + 1 < m; ++i) {
    const float la = length(r[0]), lq = length(r[i]), lt = length(r[i + 1]);
    omega += 2.0 * atan(abs(dot(r[0], cross(r[i], r[i + 1]))),
                        la * lq * lt + dot(r[0], r[i]) * lt + dot(r[0], r[i + 1]) * lq + dot(r[i], r[i + 1]) * la);
  }
}

// Band 2 of light of weight w along unit d (core/spherical_harmonics.h's shBasis).
void addBand2(vec3 d, vec3 w, inout vec3 c[9]) {
  c[4] += 1.092548 * d.x * d.y * w;
  c[5] += 1.092548 * d.y * d.z * w;
  c[6] += 0.315392 * (3.0 * d.z * d.z - 1.0) * w;
  c[7] += 1.092548 * d.x * d.z * w;
  c[8] += 0.546274 * (d.x * d.x - d.y * d.y) * w;
}

// The part of piece q (count corners) of a patch that x sees, as one direction (its irradiance
// vector's) with its solid angle: band 2 of radiance b / pi over it, scaled by `visible`.
void addPiece(vec3 x, vec3 n, vec3 q[4], int count, float visible, vec3 b, inout vec3 c[9]) {
  vec3 v;
  float omega;
  clippedMoments(x, n, q, count, v, omega);
  const float len = length(v);
  if (!(len > 0.0)) return;
  addBand2(v / len, visible * max(omega, 3.14159265 * len) / 3.14159265 * b, c);
}

// What a patch of exitance b brings point x (normal n) through the visibility-weighted factor F,
// in `count` (4 or 9) coefficients: solve/incident_sh.cpp's addPatchSh, so that the GPU's
// directions are the CPU's. Far patches (under a fifth of their distance across) as one
// direction, band 2 included; others by the moments of the polygon's part in front of x, scaled by the visible
// share F / (unoccluded factor); band 2 from k x k pieces of it, each one direction, more of them
// the nearer the patch.
void addPatchSh(vec3 x, vec3 n, GpuPatch P, float F, vec3 b, int count, inout vec3 c[9]) {
  const int pc = int(P.corners[0].w);
  vec3 q[4];
  vec3 middle = vec3(0.0);  // the corners' mean
  for (int i = 0; i < 4; ++i) q[i] = P.corners[i].xyz;
  for (int i = 0; i < pc; ++i) middle += q[i];
  middle /= float(pc);
  const vec3 toPatch = middle - x;
  const float r2 = dot(toPatch, toPatch);
  vec3 v = vec3(0.0);
  float omega = 0.0;
  if (!(P.normalArea.w < 0.04 * r2) && dot(P.normalArea.xyz, q[0] - x) < 0.0)
    clippedMoments(x, n, q, pc, v, omega);
  const float unoccluded = dot(v, n), len = length(v);
  if (!(unoccluded > 1e-7) || !(len > 0.0)) {  // far, or the centroid sees none of it: one direction
    if (!(r2 > 0.0)) return;
    const vec3 w = toPatch * inversesqrt(r2);
    const vec3 weight = F / max(dot(n, w), 0.05) * b;
    c[0] += 0.282095 * weight;
    c[1] += 0.488603 * w.y * weight, c[2] += 0.488603 * w.z * weight, c[3] += 0.488603 * w.x * weight;
    if (count > 4) addBand2(w, weight, c);
    return;
  }
  omega = max(omega, 3.14159265 * len);
  const float visible = F / unoccluded;
  const vec3 m0 = (visible * omega / 3.14159265) * b;
  c[0] += 0.282095 * m0;
  c[1] += 0.488603 * v.y * visible * b, c[2] += 0.488603 * v.z * visible * b, c[3] += 0.488603 * v.x * visible * b;
  if (count <= 4) return;
  const float across = sqrt(P.normalArea.w) / max(sqrt(r2), 1e-30);
  const int k = across < 2.0 ? max(1, int(ceil(4.0 * across))) : 8;
  if (k == 1) {
    addBand2(v / len, m0, c);
    return;
  }
  const float step = 1.0 / float(k);
  vec3 piece[4];
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) {
      if (pc == 4) {
        const float s0 = float(i) * step, t0 = float(j) * step;
        piece[0] = polygonPoint(P.corners, 4, s0, t0), piece[1] = polygonPoint(P.corners, 4, s0 + step, t0);
        piece[2] = polygonPoint(P.corners, 4, s0 + step, t0 + step), piece[3] = polygonPoint(P.corners, 4, s0, t0 + step);
        addPiece(x, n, piece, 4, visible, b, c);
      } else if (i + j < k) {
        // Barycentric sub-triangles: (i, j) upright, and the inverted one beside it when it fits.
        const vec3 e1 = (q[1] - q[0]) * step, e2 = (q[2] - q[0]) * step;
        piece[0] = q[0] + float(i) * e1 + float(j) * e2, piece[1] = piece[0] + e1, piece[2] = piece[0] + e2;
        addPiece(x, n, piece, 3, visible, b, c);
        if (i + j + 1 < k) {
          piece[0] = q[0] + float(i + 1) * e1 + float(j) * e2, piece[1] = piece[0] + e2, piece[2] = piece[0] - e1 + e2;
          addPiece(x, n, piece, 3, visible, b, c);
        }
      }
    }
}

bool isNeighbour(uint face, uint item) {
  for (uint i = faceNeighbours[face]; i < faceNeighbours[face + 1u]; ++i)
    if (faceNeighbours[i] == item) return true;
  return false;
}

// How much hemicube h sees point x (on face `ownFace`, drawn as id `item`; normal n): 1 or 0.
float seenBy(uint h, vec3 x, vec3 n, uint item, uint ownFace) {
  GpuShooter s = shooters[h];
  HemicubeFrame f = hemicubeFrame(s.normal.xyz, s.normal.w);
  vec3 r = x - s.eye.xyz;
  // The pixel nearest the projection decides. Any of the four nearest (001's rule) shrinks every
  // shadow by up to a pixel: the Cornell box's floor came out 10% bright at 64 pixels, and even
  // kept to surfaces steeper than 45 degrees it left the indirect-light room 20% bright. A
  // bilinear share of the four measured about the same as the nearest (Cornell 0.0185 against
  // 0.0200, the indirect-light room as dark).
  const ivec3 q = hemicubePixelAt(x, s.eye.xyz, f, nearPlane, farPlane, resolution, int(h));
  if (q.z < 0) return 0.0;
  float d = length(r);
  float seenAt = texelFetch(distances, q, 0).r;
  // Depth (003): the pixel's centre ray meets x's plane up to about a pixel's angle times the
  // plane's slope away from x. The allowance stops at a slope of 1.5: a larger one let light
  // through the thin walls of the indirect-light scene (NRMSE 0.146).
  if (visibility == 1) {
    float cosine = max(dot(n, -r) / d, 1e-3);
    float slope = sqrt(max(1.0 - cosine * cosine, 0.0)) / cosine;
    if (seenAt >= d * (1.0 - 3.0 * min(slope, 1.5) / float(resolution) - 1e-4)) return 1.0;
  }
  const uint seen = texelFetch(items, q, 0).r;
  if (seen == item) return 1.0;
  // The pixel's centre ray passes the point and meets something beyond it: nothing stands in
  // front. This is how a face smaller than a pixel, which the rasteriser may drop, is seen at all
  // (a 1 cm receiver under a 64-pixel hemicube came out black by its id alone).
  if (seenAt > d * (1.0 + 1e-3)) return 1.0;
  // A face that meets the point's own at a corner, no nearer than a pixel's angle times the
  // distance: the point lies beside a convex edge and its pixel shows the face round it (the
  // Cornell box's block faces edge-on to the light were half as bright as the CPU's without
  // this: NRMSE 0.022 against 0.013). Any face at all within that allowance would let light
  // through walls thinner than it (4.7 cm at 3 m and 64 pixels); a wall's far side is not a
  // neighbour of its near side.
  return seenAt >= d * (1.0 - 1.0 / float(resolution)) && isNeighbour(ownFace, seen) ? 1.0 : 0.0;
}

void main() {
  const uint e = gl_GlobalInvocationID.x;
  if (e >= elementCount) return;
  GpuElement el = elements[e];
  const vec3 n = el.normalArea.xyz;
  const int corners = int(el.corners[0].w);
  // A 2 x 2 midpoint rule over the element, for the factor and the visibility alike: both vary
  // over an element next to its source or in a penumbra, which its centre alone misses.
  vec3 x[4];
  for (int q = 0; q < 4; ++q) x[q] = polygonPoint(el.corners, corners, 0.25 + 0.5 * float(q & 1), 0.25 + 0.5 * float(q >> 1));
  vec3 dh = vec3(0.0), dd = vec3(0.0);
  vec3 sh[9];
  for (int i = 0; i < 9; ++i) sh[i] = vec3(0.0);
  bool reached = false;     // some shot reached it: its directions change
  vec3 centre = vec3(0.0);  // the corners' mean: the centroid of a triangle or parallelogram
  for (int i = 0; i < corners; ++i) centre += el.corners[i].xyz / float(corners);
  bool shooter = false;
  for (uint k = 0u; k < state.chosen; ++k) {
    GpuShooter s = shooters[k * samples];
    const uint p = s.ids.x;
    shooter = shooter || p == el.ids.y;
    GpuPatch P = patches[p];
    if (P.ids.z == el.ids.z) continue;  // no face lights itself
    float F = 0.0;
    // Cross projection (cross_redistribution_gl.h): what each receiver point sees behind the moved
    // shooter, weighted by its part of F; a static receiver's only.
    const bool crossing = crossProjecting && (crossPatches[el.ids.y].x & 1u) == 0u;
    vec3 behind = vec3(0.0), emittedBehind = vec3(0.0);
    for (int q = 0; q < 4; ++q) {
      float f = pointToPolygonFormFactor(x[q], n, P.corners, int(P.corners[0].w), P.normalArea.xyz);
      if (f <= 0.0) continue;
      // The share of the hemicubes that see the point, each weighted by its point-to-point
      // kernel cos cos / r^2 (CpuTransport's estimator): near parts of the patch carry more of
      // f, and an unweighted share came out 2-22% low in the Cornell box's interreflections.
      // Hemicubes behind the point's plane weigh nothing: f integrates only the part of the
      // patch in front, and from behind the plane the point's own surface hides it.
      float seen = 0.0, all = 0.0;
      for (uint j = 0u; j < samples; ++j) {
        const uint h = k * samples + j;
        const vec3 d = shooters[h].eye.xyz - x[q];
        const float r2 = dot(d, d), g = max(dot(n, d), 0.0) * max(-dot(P.normalArea.xyz, d), 0.0) / (r2 * r2);
        if (!(g > 0.0)) continue;
        all += g;
        seen += g * seenBy(h, x[q], n, el.ids.x, el.ids.z);
      }
      const float Fq = all > 0.0 ? f * seen / all : 0.0;
      F += Fq;
      if (crossing && Fq > 0.0) {
        vec3 shotHere, emittedHere;
        // Mean radiosity behind P: as the element's patch centre sees it, or from this point.
        const uint b = 2u * (k * crossPatchCount + el.ids.y);
        if (crossPatchCount > 0u && crossBehind[b].w > 0.0)
          shotHere = crossBehind[b].rgb, emittedHere = crossBehind[b + 1u].rgb;
        else
          crossProjected(k, x[q], n, P, shotHere, emittedHere);
        behind += Fq * shotHere, emittedBehind += Fq * emittedHere;
        emittersHidden(x[q], n, P, shotHere, emittedHere);  // irradiance P hides, were all of P seen
        behind += (Fq / f) * shotHere, emittedBehind += (Fq / f) * emittedHere;
      }
    }
    F *= 0.25;
    dh += F * s.unshot.rgb;
    dd += F * s.emission.rgb;
    dh -= crossSign * 0.25 * behind;
    dd -= crossSign * 0.25 * emittedBehind;
    if (shCount > 0 && F != 0.0) {
      addPatchSh(centre, n, P, F, s.unshot.rgb, shCount, sh);
      reached = true;
    }
  }
  // Not only where dh is non-zero: a redistribution's shots of both signs can cancel in dh alone.
  if (reached)
    for (int i = 0; i < shCount; ++i) elementSh[uint(shCount) * e + uint(i)].rgb += sh[i];
  if (redistributing) shooter = false;
  if (!shooter && dh == vec3(0.0) && dd == vec3(0.0)) return;
  GpuElementState st = states[e];
  const vec3 db = el.reflectance.rgb * dh;
  st.radiosity.rgb += db;
  st.irradiance.rgb += dh;
  st.direct.rgb += dd;
  st.unshot.rgb = (shooter ? vec3(0.0) : st.unshot.rgb) + db;
  states[e] = st;
}
)";

// Redistribution (followChanges), van de Hoef 2013 Sec. 3.1 and 4.4, Chen 1990: progressive
// refinement keeps B = E + rho H, H the analytic irradiance plus what every patch has shot
// through its factors. After a move every patch shoots what it has shot again, negated, from
// where everything stood (the old geometry still in the buffers and the hemicubes' mesh), and
// again, positive, from where everything stands: H moves by sum_p (F' - F) S_p, with the same
// hemicube turns in both passes so that a pair the move did not touch cancels. The emission a
// shot emitter's first shot carried moves the direct light the same way. What the new H means
// for B and the unshot radiosity (and any change of analytic light, emission or reflectance) is
// the rebase pass's; progressive shooting then spends the difference, negative light included.

// a. Per patch: the area mean of the radiosity its elements have shot (B - unshot), and the
// emission its first shot carried (zero when it has not shot). Read before anything changes.
const char* kAmountsCompute = R"(
layout(local_size_x = POWER_GROUP) in;
layout(std430, binding = REDISTRIBUTION_AMOUNT_BINDING) writeonly buffer Amounts { vec4 amounts[]; };
uniform uint patchCount;
void main() {
  uint p = gl_GlobalInvocationID.x;
  if (p >= patchCount) return;
  GpuPatch P = patches[p];
  vec3 sum = vec3(0.0);
  for (uint i = P.ids.x; i < P.ids.x + P.ids.y; ++i) {
    uint e = patchElements[i];
    sum += elements[e].normalArea.w * (states[e].radiosity.rgb - states[e].unshot.rgb);
  }
  amounts[2u * p] = vec4(P.normalArea.w > 0.0 ? sum / P.normalArea.w : vec3(0.0), 0.0);
  amounts[2u * p + 1u] = vec4(patchStates[p].shot != 0u ? P.emission.rgb : vec3(0.0), 0.0);
}
)";

// b. The shooters of one redistribution pass: patches list[first .. first + count), k x k
// hemicubes each, shooting sign times their amounts. The turns depend on the patch and the
// sample only, so the negative and the positive pass draw the same hemicubes.
const char* kRedistributeCompute = R"(
layout(local_size_x = POWER_GROUP) in;
layout(std430, binding = REDISTRIBUTION_AMOUNT_BINDING) readonly buffer Amounts { vec4 amounts[]; };
layout(std430, binding = REDISTRIBUTION_LIST_BINDING) readonly buffer List { uint list[]; };
uniform uint first, count, samplesPerSide;
uniform float sign, offset;
uniform bool emissionOnly;  // only the direct light a first shot carried
uniform bool emissionAsLight;  // with emissionOnly: that emission is shot as light too
// Cross-redistribution: each patch's back hemicube, at its corners' mean just behind it, facing
// the other way (cross_redistribution_gl.h).
uniform bool crossing;
layout(std430, binding = BACK_SHOOTER_BINDING) writeonly buffer BackShooters { GpuShooter backShooters[]; };
void main() {
  const uint r = gl_GlobalInvocationID.x, samples = samplesPerSide * samplesPerSide;
  if (r >= count * samples) return;
  const uint k = r / samples, j = r % samples, p = list[first + k];
  GpuPatch P = patches[p];
  const float ks = float(samplesPerSide);
  vec3 x = polygonPoint(P.corners, int(P.corners[0].w), (float(j % samplesPerSide) + 0.5) / ks,
                        (float(j / samplesPerSide) + 0.5) / ks);
  const vec3 shot = emissionOnly ? (emissionAsLight ? amounts[2u * p + 1u].rgb : vec3(0.0)) : amounts[2u * p].rgb;
  shooters[r] = GpuShooter(vec4(x + offset * P.normalArea.xyz, 0.0), vec4(P.normalArea.xyz, hemicubeTurn(p, j, 0x5EEDu)),
                           vec4(sign * shot, 0.0), vec4(sign * amounts[2u * p + 1u].rgb, 0.0), uvec4(p, 1u, 0u, 0u));
  if (r == 0u) state.chosen = count;
  if (crossing && j == 0u) {
    const int corners = int(P.corners[0].w);
    vec3 centre = vec3(0.0);
    for (int c = 0; c < corners; ++c) centre += P.corners[c].xyz / float(corners);
    backShooters[k] = GpuShooter(vec4(centre - offset * P.normalArea.xyz, 0.0),
                                 vec4(-P.normalArea.xyz, hemicubeTurn(p, 0u, 0xBAC5u)), vec4(0.0), vec4(0.0),
                                 uvec4(p, 1u, 0u, 0u));
  }
}
)";

// c. Rebase: each element's irradiance moves by the analytic light's change, and its radiosity
// becomes E + rho H with the (new) emission and reflectance; the difference is unshot. An
// emission change that a redistribution has already shot as light (emissionAsLight) is not
// unshot again: it is added to the radiosity first.
const char* kRebaseCompute = R"(
layout(local_size_x = RECONSTRUCT_GROUP) in;
layout(std430, binding = REDISTRIBUTION_AMOUNT_BINDING) readonly buffer Inputs { vec4 inputs[]; };  // E', rho', dH0, dE
uniform uint elementCount;
uniform bool emissionShot;
void main() {
  const uint e = gl_GlobalInvocationID.x;
  if (e >= elementCount) return;
  GpuElementState st = states[e];
  const vec3 emission = inputs[4u * e].rgb, reflectance = inputs[4u * e + 1u].rgb, dh = inputs[4u * e + 2u].rgb;
  if (emissionShot && patchStates[elements[e].ids.y].shot != 0u) st.radiosity.rgb += inputs[4u * e + 3u].rgb;
  st.irradiance.rgb += dh;
  st.direct.rgb += dh;
  const vec3 b = emission + reflectance * st.irradiance.rgb;
  st.unshot.rgb += b - st.radiosity.rgb;
  st.radiosity.rgb = b;
  states[e] = st;
}
)";

// The GL objects of one solve, released on every path out (exceptions included).
struct Buffers {
  GLuint elements = 0, patches = 0, patchElements = 0, patchStates = 0, shooters = 0, state = 0, elementStates = 0;
  GLuint faceNeighbours = 0;
  GLuint amounts = 0, list = 0, rebase = 0;  // redistribution only
  GLuint elementSh = 0;                      // recordIncidentSh only
  ~Buffers() {
    const GLuint all[] = {elements,      patches,        patchElements, patchStates, shooters, state,
                          elementStates, faceNeighbours, amounts,       list,        rebase,   elementSh};
    glDeleteBuffers(GLsizei(std::size(all)), all);
  }
  void bind() const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kElementBinding, elements);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPatchBinding, patches);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPatchElementBinding, patchElements);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPatchStateBinding, patchStates);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kShooterBinding, shooters);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSolverStateBinding, state);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kFaceNeighbourBinding, faceNeighbours);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kElementStateBinding, elementStates);
    if (elementSh) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kElementShBinding, elementSh);
  }
};

GLuint groups(size_t n, int size) { return GLuint((n + size_t(size) - 1) / size_t(size)); }


class GlProgressiveSolver final : public Solver {
 public:
  GlProgressiveSolver(const RadiositySystem& sys, Context& context, const GlProgressiveSettings& o,
                      std::vector<uint32_t> objectOfPatch)
      : sys_(sys), device_(context.renderer()), o_(o) {
    const Stopwatch watch;
    const SurfaceSet& set = sys.surfaces;
    const size_t ne = sys.elementCount(), np = sys.patchCount();

    // Inputs, once (again after a move, with followChanges).
    const std::vector<GpuElement> elements = elementRecords();
    std::vector<GpuElementState> states(ne);
    for (size_t e = 0; e < ne; ++e) {
      const Rgb b = sys.emission[e] + sys.reflectance[e] * sys.analytic[e];
      states[e] = {glm::vec4(b, 0.0f), glm::vec4(b, 0.0f), glm::vec4(sys.analytic[e], 0.0f), glm::vec4(sys.analytic[e], 0.0f)};
    }
    analyticUsed_ = sys.analytic;
    emissionUsed_ = sys.emission;
    patchEmissionUsed_ = sys.patchMeans(sys.emission);
    const GpuPatches patches = gpuPatches(sys);

    const float extent = set.sceneExtent > 0.0f ? set.sceneExtent : 1.0f;
    samples_ = o.samplesPerSide * o.samplesPerSide;
    batch_ = int(std::min<size_t>(size_t(o.shootersPerPass), std::max<size_t>(np, 1)));
    // Emitters first, each with its own k_e x k_e hemicubes, as many per pass as fit the layers of
    // a regular pass (at least one).
    // Following changes, every shot of a patch uses the same hemicubes (same number, same turns),
    // which a redistribution draws again: an emitter's first shot with more of them than its later
    // shots would leave the difference behind at every move.
    // Cross-redistribution keeps the emitters' own: it never shoots a static emitter's light
    // again after a move, and a light edit shoots the emission's change as light with them
    // (sourcesChanged). A moving emitter shoots all it has shot with them, which leaves its later
    // shots' difference between the two hemicube sets (small: they carry reflected light only).
    const bool ownEmitterHemicubes = !o.followChanges || o.crossRedistribution;
    emitterSide_ = o.emitterSamplesPerSide > 0 && ownEmitterHemicubes ? o.emitterSamplesPerSide : o.samplesPerSide;
    emitterSamples_ = emitterSide_ * emitterSide_;
    emitterBatch_ = std::clamp(batch_ * samples_ / emitterSamples_, 1, batch_);
    for (const GpuPatch& p : patches.patches) emitters_ += p.emission.r + p.emission.g + p.emission.b > 0.0f ? 1 : 0;
    emittersApart_ = emitterSide_ != o.samplesPerSide && emitters_ > 0;
    std::vector<Polygon> facePolygons;
    std::vector<uint32_t> faceItems;
    LayeredHemicubes::faceItems(set, facePolygons, faceItems);
    // Room for a regular pass or an emitters' pass, whichever needs more hemicubes; following
    // changes, for a redistribution pass of as many patches as the layers allow (up to
    // kMaxShootersPerPass): every patch shoots in a redistribution, in no particular order, so
    // the largest batch costs least.
    int capacity = std::max(batch_ * samples_, emittersApart_ ? emitterBatch_ * emitterSamples_ : 0);
    if (o.followChanges) {
      GLint maxLayers = 0;
      glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
      redistributionBatch_ = std::clamp(int(maxLayers) / (5 * samples_), 1, kMaxShootersPerPass);
      capacity = std::max(capacity, redistributionBatch_ * samples_);
    }
    hemicubes_ = std::make_unique<LayeredHemicubes>(facePolygons, faceItems,
                                                    LayeredHemicubes::Content::ItemsAndDistances, o.resolution,
                                                    capacity, o.nearPlane * extent, 2.0f * extent, o.layering);

    buf_.elements = storageBuffer(elements.data(), elements.size() * sizeof(GpuElement));
    buf_.patches = storageBuffer(patches.patches.data(), patches.patches.size() * sizeof(GpuPatch));
    buf_.patchElements = storageBuffer(patches.elements.data(), patches.elements.size() * sizeof(uint32_t));
    std::vector<GpuPatchState> patchStates(np, GpuPatchState{0.0f, 0u});
    buf_.patchStates = storageBuffer(patchStates.data(), patchStates.size() * sizeof(GpuPatchState));
    buf_.shooters = storageBuffer(nullptr, size_t(capacity) * sizeof(GpuShooter));
    GpuSolverState initial{};
    buf_.state = storageBuffer(&initial, sizeof initial);
    buf_.elementStates = storageBuffer(states.data(), states.size() * sizeof(GpuElementState));
    const std::vector<uint32_t> neighbours = LayeredHemicubes::neighbourItems(set);
    buf_.faceNeighbours = storageBuffer(neighbours.data(), neighbours.size() * sizeof(uint32_t));

    const std::string preamble = glslPreamble() + kHemicubeGlsl + kFormFactorGlsl + kBuffersGlsl;
    power_ = std::make_unique<ShaderProgram>("patch power", preamble + kPowerCompute);
    select_ = std::make_unique<ShaderProgram>("shooter selection", preamble + kSelectCompute);
    reconstruct_ = std::make_unique<ShaderProgram>("shot reconstruction", preamble + crossProjectionGlsl() + kReconstructCompute);
    auto uniform = [](const ShaderProgram& p, const char* name) { return glGetUniformLocation(p.id(), name); };
    power_->use();
    glUniform1ui(uniform(*power_, "patchCount"), GLuint(np));
    select_->use();
    glUniform1ui(uniform(*select_, "patchCount"), GLuint(np));
    glUniform1ui(uniform(*select_, "shotLimit"),
                 o.shotBudget ? GLuint(std::min<uint64_t>(o.shotBudget, 0xFFFFFFFFu)) : 0xFFFFFFFFu);
    sourcePower_ = sys.sourcePower();
    glUniform1f(uniform(*select_, "stopPower"), float(o.unshotThreshold * sourcePower_));
    offset_ = o.offset * extent;
    glUniform1f(uniform(*select_, "offset"), offset_);
    stopPowerUniform_ = uniform(*select_, "stopPower");
    glUniform1i(uniform(*select_, "fixedTurns"), o.followChanges);
    selectBatch_ = uniform(*select_, "batch"), selectSide_ = uniform(*select_, "samplesPerSide"),
    selectEmitters_ = uniform(*select_, "emittersOnly");
    reconstruct_->use();
    glUniform1ui(uniform(*reconstruct_, "elementCount"), GLuint(ne));
    glUniform1i(uniform(*reconstruct_, "resolution"), o.resolution);
    glUniform1i(uniform(*reconstruct_, "visibility"), o.visibility == HemicubeVisibility::Item ? 0 : 1);
    glUniform1f(uniform(*reconstruct_, "nearPlane"), hemicubes_->nearPlane());
    glUniform1f(uniform(*reconstruct_, "farPlane"), hemicubes_->farPlane());
    reconstructSamples_ = uniform(*reconstruct_, "samples");
    reconstructRedistributing_ = uniform(*reconstruct_, "redistributing");
    glUniform1i(reconstructRedistributing_, 0);
    glUniform1i(uniform(*reconstruct_, "shCount"), 0);
    reconstructCrossProjecting_ = uniform(*reconstruct_, "crossProjecting");
    reconstructCrossSign_ = uniform(*reconstruct_, "crossSign");
    glUniform1i(reconstructCrossProjecting_, 0);
    if (o.followChanges) {
      amounts_ = std::make_unique<ShaderProgram>("redistribution amounts", preamble + kAmountsCompute);
      redistribute_ = std::make_unique<ShaderProgram>("redistribution shooters", preamble + kRedistributeCompute);
      rebase_ = std::make_unique<ShaderProgram>("redistribution rebase", preamble + kRebaseCompute);
      amounts_->use();
      glUniform1ui(uniform(*amounts_, "patchCount"), GLuint(np));
      redistribute_->use();
      glUniform1f(uniform(*redistribute_, "offset"), offset_);
      rebase_->use();
      glUniform1ui(uniform(*rebase_, "elementCount"), GLuint(ne));
      buf_.amounts = storageBuffer(nullptr, std::max(2 * np, 4 * ne) * sizeof(glm::vec4));
      if (o.crossRedistribution) {
        cross_ = std::make_unique<CrossRedistribution>(sys, std::move(objectOfPatch), o.cross, redistributionBatch_,
                                                       hemicubes_->nearPlane(), hemicubes_->farPlane(), offset_,
                                                       preamble);
        cross_->setReconstructionUniforms(reconstruct_->id(), emitterSide_);
      }
    }
    Context::check("setting up GPU progressive refinement");
    setupSeconds_ = watch.seconds();
  }

  bool step(const StepLimit& limit, const ProgressCallback& progress) override {
    const Stopwatch watch;
    // Following changes, a step with nothing changed since the solve stopped goes a decade
    // further (see settleThreshold).
    if (o_.followChanges && done_ && threshold_ > o_.settleThreshold && unshotFraction_ > o_.settleThreshold &&
        !(o_.shotBudget && shots_ >= o_.shotBudget) && !(o_.timeBudget > 0.0 && seconds_ >= o_.timeBudget)) {
      setThreshold(std::max(o_.settleThreshold, threshold_ * 0.1));
      done_ = false;
    }
    if (emittersApart_ && !emittersShot_) {
      for (size_t shot = 0; shot < emitters_; shot += size_t(emitterBatch_)) shoot(emitterBatch_, emitterSide_, true);
      emitterShots_ = readState().shots;
      emittersShot_ = true;
    }
    uint64_t units = 0;
    while (!done_) {
      if (sliceSpent(limit, units, watch)) break;
      if (o_.timeBudget > 0.0 && seconds_ + watch.seconds() >= o_.timeBudget) {
        done_ = true;
        break;
      }
      for (int pass = 0; pass < o_.passesPerCheck; ++pass) shoot(batch_, o_.samplesPerSide, false);
      ++units;
      timeline_.mark("shoot: read state");
      const GpuSolverState s = readState();  // the only read-back while shooting: a few bytes every few passes
      timeline_.collect();  // what the read-back waited for: keeps a long step's open queries few
      Context::check("GPU progressive refinement");
      shots_ = s.shots;
      unshotFraction_ = sourcePower_ > 0.0 ? s.unshotPower / sourcePower_ : 0.0;
      if (s.chosen == 0) {  // converged, or the shot budget is spent: the GPU stopped itself
        done_ = true;
        break;
      }
      const double shown =
          std::clamp(std::log(std::max(unshotFraction_, 1e-30)) / std::log(threshold_), 0.0, 1.0);
      if (throttle_.due(shown))
        reportProgress(progress, "solve", shown, fmt::format("unshot {:.3f}%", 100.0 * unshotFraction_));
    }
    timeline_.mark("finish");
    glFinish();  // the step's GPU work belongs to its time
    timeline_.stop();
    timeline_.collect();
    seconds_ += watch.seconds();
    if (done_) reportProgress(progress, "solve", 1.0, fmt::format("unshot {:.3f}%", 100.0 * unshotFraction_));
    return !done_;
  }

  bool done() const override { return done_; }

  Solution solution() override {
    const Stopwatch watch;
    const size_t ne = sys_.elementCount();
    choose(0, o_.samplesPerSide, false);  // the unshot power left
    const GpuSolverState s = readState();
    timeline_.stop();
    timeline_.collect();  // now, not in the next step's: its time is this call's
    std::vector<GpuElementState> states(ne);
    glGetNamedBufferSubData(buf_.elementStates, 0, GLsizeiptr(ne * sizeof(GpuElementState)), states.data());
    Context::check("reading back the GPU solution");
    shots_ = s.shots;
    unshotFraction_ = sourcePower_ > 0.0 ? s.unshotPower / sourcePower_ : 0.0;
    Solution sol = solutionFromStates(states);
    std::vector<Rgb> unshot(ne);
    for (size_t e = 0; e < ne; ++e) unshot[e] = Rgb(states[e].unshot);
    if (o_.ambient) addAmbientTerm(sys_, unshot, sol.radiosity, sol.irradiance);
    sol.unshot = std::move(unshot);
    seconds_ += watch.seconds();
    sol.stats = stats();
    return sol;
  }

  // L1 or L2, only from the first shot on: each shot adds what it brings along its exact
  // directions (addPatchSh above), so the sum is the CPU's pass over what every patch has shot.
  void recordIncidentSh(int count) override {
    if ((count != kShL1Coefficients && count != kShCoefficients) || buf_.elementSh || shots_ > 0 || emittersShot_)
      return;
    const std::vector<glm::vec4> zero(size_t(count) * sys_.elementCount(), glm::vec4(0.0f));
    buf_.elementSh = storageBuffer(zero.data(), zero.size() * sizeof(glm::vec4));
    shCount_ = count;
    reconstruct_->use();
    glUniform1i(glGetUniformLocation(reconstruct_->id(), "shCount"), count);
    Context::check("recording directions on the GPU");
  }

  bool incidentSh(int count, std::span<Rgb> out) override {
    // None recorded, or not these, or moved by cross projection, which does not carry directions:
    // the owner gathers them.
    if (count != shCount_ || crossMoved_) return false;
    const size_t ne = sys_.elementCount();
    std::vector<glm::vec4> sh(size_t(count) * ne);
    glGetNamedBufferSubData(buf_.elementSh, 0, GLsizeiptr(sh.size() * sizeof(glm::vec4)), sh.data());
    Context::check("reading back the GPU's directions");
    for (size_t i = 0; i < sh.size(); ++i) out[i] = Rgb(sh[i]);
    // The ambient term, where it is on, arrives evenly over the hemisphere (as on the CPU).
    if (o_.ambient) {
      std::vector<GpuElementState> states(ne);
      glGetNamedBufferSubData(buf_.elementStates, 0, GLsizeiptr(ne * sizeof(GpuElementState)), states.data());
      std::vector<Rgb> unshot(ne), radiosity(ne), irradiance(ne), before(ne);
      for (size_t e = 0; e < ne; ++e)
        unshot[e] = Rgb(states[e].unshot), radiosity[e] = Rgb(states[e].radiosity),
        irradiance[e] = before[e] = Rgb(states[e].irradiance);
      addAmbientTerm(sys_, unshot, radiosity, irradiance);
      for (size_t e = 0; e < ne; ++e)
        shAddUniformHemisphere(out.data() + e * size_t(count), count, sys_.surfaces.elements[e].normal,
                               irradiance[e] - before[e]);
    }
    return true;
  }

  // The element and patch states and the solver's counters, read back from the GPU; the
  // hemicubes and the shooters' buffer are scratch, drawn anew each pass. Recorded directions are
  // not kept: a solve resumed from a checkpoint gathers them instead.
  bool checkpoints() const override { return true; }
  void saveState(StateWriter& out) const override {
    for (GLuint b : {buf_.elementStates, buf_.patchStates, buf_.state}) saveBuffer(b, out);
    out.value(emittersShot_), out.value(emitterShots_), out.value(shots_), out.value(unshotFraction_);
    out.value(seconds_), out.value(done_);
  }
  void restoreState(StateReader& in) override {
    for (GLuint b : {buf_.elementStates, buf_.patchStates, buf_.state}) restoreBuffer(b, in);
    if (cross_) cross_->geometryMoved();  // no gather hemicubes kept from before the checkpoint
    shCount_ = 0;
    in.value(emittersShot_), in.value(emitterShots_), in.value(shots_), in.value(unshotFraction_);
    in.value(seconds_), in.value(done_);
  }

  bool objectsMoved(std::span<const uint32_t> objects) override {
    if (!o_.followChanges) return false;
    const Stopwatch watch;
    if (cross_) {
      timeline_.mark("move: moved set");
      cross_->begin(objects);
      if (cross_->closedToOutside()) {
        crossRedistribute();
        changed(watch);
        return true;
      }
      if (!openMoverWarned_) {
        openMoverWarned_ = true;
        warnings_.push_back("cross-redistribution: a moved object has one-sided faces whose backs can be seen (an open "
                            "mesh), which the cross projection cannot follow: its moves are redistributed as by "
                            "incremental, every patch shooting again");
      }
    }
    std::vector<uint32_t> emitters, others;
    const std::vector<Rgb> emission = sys_.patchMeans(sys_.emission);
    for (uint32_t p = 0; p < sys_.patchCount(); ++p) (channelSum(emission[p]) > 0.0 ? emitters : others).push_back(p);
    computeAmounts();
    redistribute(-1.0f, emitters, others);  // from where everything was: the buffers and mesh still say so
    uploadGeometry();
    if (cross_) cross_->geometryMoved();
    redistribute(1.0f, emitters, others);   // from where everything is
    rebase();
    changed(watch);
    return true;
  }

  bool sourcesChanged() override {
    if (!o_.followChanges) return false;
    const Stopwatch watch;
    // The direct light of emitters that have shot and whose emission changed: what their first
    // shot carried, moved from the old emission to the new (the scattered light follows by
    // rebase and shooting, as for any change). Where emitters shoot first with hemicubes of
    // their own, the change is shot as light with them here too, as a fresh solve's first shot
    // would, not left to the later shots' hemicubes.
    const bool asLight = emitterSide_ != o_.samplesPerSide;
    const std::vector<Rgb> emission = sys_.patchMeans(sys_.emission);
    std::vector<uint32_t> changedEmitters;
    for (uint32_t p = 0; p < sys_.patchCount(); ++p)
      if (emission[p] != patchEmissionUsed_[p]) changedEmitters.push_back(p);
    if (!changedEmitters.empty()) {
      computeAmounts();
      redistribute(-1.0f, changedEmitters, {}, /*emissionOnly=*/true, false, asLight);
    }
    uploadGeometry();
    if (!changedEmitters.empty()) {
      computeAmounts();
      redistribute(1.0f, changedEmitters, {}, /*emissionOnly=*/true, false, asLight);
    }
    rebase(asLight);
    changed(watch);
    return true;
  }

  SolveStats stats() const override {
    SolveStats st;
    st.method = cross_ ? "cross-redistribution" : o_.followChanges ? "incremental" : "progressive";
    st.warnings = warnings_;
    st.backend = "gl";
    st.redistributions = redistributions_;
    st.secondsRedistribution = secondsRedistributing_;
    st.device = device_;
    st.shots = shots_;
    const uint64_t emitterShots = std::min<uint64_t>(emitterShots_, shots_);
    st.hemicubes = emitterShots * uint64_t(emitterSamples_) + (shots_ - emitterShots) * uint64_t(samples_);
    st.unshotFraction = st.residual = unshotFraction_;
    // Everything on the GPU is form factors and their use at once: one figure, as the seed's.
    st.secondsFormFactors = setupSeconds_ + seconds_;
    st.phases = timeline_.totals();
    return st;
  }

 private:
  // The elements as the GPU reads them, where the surfaces say they are now.
  std::vector<GpuElement> elementRecords() const {
    const SurfaceSet& set = sys_.surfaces;
    std::vector<GpuElement> elements(sys_.elementCount());
    for (size_t e = 0; e < elements.size(); ++e) {
      const Element& el = set.elements[e];
      GpuElement& g = elements[e];
      for (int c = 0; c < 4; ++c) g.corners[c] = glm::vec4(el.polygon.v[size_t(c)], 0.0f);
      g.corners[0].w = float(el.polygon.count);
      g.normalArea = glm::vec4(el.normal, sys_.area[e]);
      g.reflectance = glm::vec4(sys_.reflectance[e], 0.0f);
      g.ids = glm::uvec4(LayeredHemicubes::itemOfFace(set, el.face), el.patch, el.face, 0u);
    }
    return elements;
  }

  // Redistribution (see the shaders above). Each patch's shot radiosity and first-shot emission,
  // before anything changes.
  void computeAmounts() {
    timeline_.mark("move: amounts");
    buf_.bind();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRedistributionAmountBinding, buf_.amounts);
    amounts_->use();
    glDispatchCompute(groups(sys_.patchCount(), kPowerGroup), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }

  // Every patch in `emitters` (with the emitters' k_e x k_e hemicubes) and `others` shoots `sign`
  // times its amounts, batch by batch, without spending anyone's unshot radiosity.
  // Crossing (cross-redistribution): the patches are the moved ones, and each pass's static
  // receivers also take the cross projection of what the patches hide (cross_redistribution_gl.h).
  void redistribute(float sign, const std::vector<uint32_t>& emitters, const std::vector<uint32_t>& others,
                    bool emissionOnly = false, bool crossing = false, bool emissionAsLight = false) {
    std::vector<uint32_t> list = emitters;
    list.insert(list.end(), others.begin(), others.end());
    if (list.empty()) return;
    if (listCapacity_ < list.size()) {
      glDeleteBuffers(1, &buf_.list);
      buf_.list = storageBuffer(nullptr, list.size() * sizeof(uint32_t));
      listCapacity_ = list.size();
    }
    glNamedBufferSubData(buf_.list, 0, GLsizeiptr(list.size() * sizeof(uint32_t)), list.data());
    auto uniform = [](const ShaderProgram& p, const char* name) { return glGetUniformLocation(p.id(), name); };
    const struct {
      size_t first, count;
      int side, batch;
    } groupsOf[2] = {{0, emitters.size(), emitterSide_, redistributionBatch_},
                     {emitters.size(), others.size(), o_.samplesPerSide, redistributionBatch_}};
    for (const auto& g : groupsOf) {
      for (size_t done = 0; done < g.count; done += size_t(g.batch)) {
        const int count = int(std::min(size_t(g.batch), g.count - done)), samples = g.side * g.side;
        timeline_.mark("redistribute: shooters");
        buf_.bind();
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRedistributionAmountBinding, buf_.amounts);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRedistributionListBinding, buf_.list);
        redistribute_->use();
        glUniform1ui(uniform(*redistribute_, "first"), GLuint(g.first + done));
        glUniform1ui(uniform(*redistribute_, "count"), GLuint(count));
        glUniform1ui(uniform(*redistribute_, "samplesPerSide"), GLuint(g.side));
        glUniform1f(uniform(*redistribute_, "sign"), sign);
        glUniform1i(uniform(*redistribute_, "emissionOnly"), emissionOnly);
        glUniform1i(uniform(*redistribute_, "emissionAsLight"), emissionAsLight);
        glUniform1i(uniform(*redistribute_, "crossing"), crossing);
        if (crossing) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBackShooterBinding, cross_->backShooters());
        glDispatchCompute(groups(size_t(count * samples), kPowerGroup), 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        timeline_.mark("redistribute: hemicubes");
        hemicubes_->render(0, count * samples);
        if (crossing) {
          timeline_.mark("redistribute: back hemicubes");
          cross_->renderBackHemicubes(count);
          buf_.bind();  // the shooters' buffer again in SHOOTER_BINDING
          glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRedistributionAmountBinding, buf_.amounts);
          cross_->bindForReconstruction();
          timeline_.mark("redistribute: behind the movers");
          cross_->projectBehind(count, samples);
        }
        timeline_.mark("redistribute: reconstruct");
        hemicubes_->bindTextures();
        reconstruct_->use();
        glUniform1ui(reconstructSamples_, GLuint(samples));
        glUniform1i(reconstructRedistributing_, 1);
        glUniform1i(reconstructCrossProjecting_, crossing);
        glUniform1f(reconstructCrossSign_, sign);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
        glDispatchCompute(groups(sys_.elementCount(), kReconstructGroup), 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        glUniform1i(reconstructRedistributing_, 0);
        glUniform1i(reconstructCrossProjecting_, 0);
      }
    }
  }

  // Cross-redistribution after `objects` moved (cross_redistribution_gl.h): the moved patches
  // shoot, with the cross projection of the static light they hid or uncover, and the moved
  // elements gather the static patches' light; each from where things were (negative), then, the
  // new geometry uploaded, from where they are.
  void crossRedistribute() {
    const std::vector<Rgb> emission = sys_.patchMeans(sys_.emission);
    std::vector<uint32_t> emitters, others;
    for (uint32_t p = 0; p < sys_.patchCount(); ++p)
      if (cross_->moved(p)) (channelSum(emission[p]) > 0.0 ? emitters : others).push_back(p);
    computeAmounts();
    for (const float sign : {-1.0f, 1.0f}) {
      if (sign > 0.0f) {
        uploadGeometry();
        timeline_.mark("move: gather geometry");
        cross_->geometryMoved();
      }
      redistribute(sign, emitters, others, false, /*crossing=*/true);
      cross_->gatherMoved(sign, buf_.elements, buf_.patches, buf_.elementStates, buf_.amounts, timeline_);
    }
    rebase();
    crossMoved_ = true;
  }

  // The surfaces' current geometry, reflectance and emission into the buffers and the mesh.
  void uploadGeometry() {
    timeline_.mark("move: upload geometry");
    const std::vector<GpuElement> elements = elementRecords();
    glNamedBufferSubData(buf_.elements, 0, GLsizeiptr(elements.size() * sizeof(GpuElement)), elements.data());
    const GpuPatches patches = gpuPatches(sys_);
    glNamedBufferSubData(buf_.patches, 0, GLsizeiptr(patches.patches.size() * sizeof(GpuPatch)), patches.patches.data());
    std::vector<Polygon> facePolygons;
    std::vector<uint32_t> faceItems;
    LayeredHemicubes::faceItems(sys_.surfaces, facePolygons, faceItems);
    hemicubes_->setPolygons(facePolygons, faceItems);
    const std::vector<uint32_t> neighbours = LayeredHemicubes::neighbourItems(sys_.surfaces);
    glDeleteBuffers(1, &buf_.faceNeighbours);
    buf_.faceNeighbours = storageBuffer(neighbours.data(), neighbours.size() * sizeof(uint32_t));
  }

  // Irradiance by the analytic light's change, radiosity to E + rho H, the difference unshot.
  // `emissionShot`: the emission's change since the last update was shot as light already, by the
  // emitters that have shot.
  void rebase(bool emissionShot = false) {
    timeline_.mark("move: rebase");
    const size_t ne = sys_.elementCount();
    std::vector<glm::vec4> inputs(4 * ne);
    for (size_t e = 0; e < ne; ++e)
      inputs[4 * e] = glm::vec4(sys_.emission[e], 0.0f), inputs[4 * e + 1] = glm::vec4(sys_.reflectance[e], 0.0f),
      inputs[4 * e + 2] = glm::vec4(sys_.analytic[e] - analyticUsed_[e], 0.0f),
      inputs[4 * e + 3] = glm::vec4(sys_.emission[e] - emissionUsed_[e], 0.0f);
    glNamedBufferSubData(buf_.amounts, 0, GLsizeiptr(inputs.size() * sizeof(glm::vec4)), inputs.data());
    buf_.bind();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRedistributionAmountBinding, buf_.amounts);
    rebase_->use();
    glUniform1i(glGetUniformLocation(rebase_->id(), "emissionShot"), emissionShot);
    glDispatchCompute(groups(ne, kReconstructGroup), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }

  // After a redistribution: new stopping power, and shooting goes on.
  void changed(const Stopwatch& watch) {
    analyticUsed_ = sys_.analytic;
    emissionUsed_ = sys_.emission;
    patchEmissionUsed_ = sys_.patchMeans(sys_.emission);
    sourcePower_ = sys_.sourcePower();
    setThreshold(o_.unshotThreshold);
    done_ = false;
    timeline_.mark("move: finish");
    glFinish();  // the redistribution's GPU work belongs to its time
    timeline_.stop();
    timeline_.collect();
    Context::check("GPU redistribution");
    ++redistributions_;
    secondsRedistributing_ += watch.seconds();
    seconds_ += watch.seconds();
  }

  // The unshot fraction the GPU stops shooting at.
  void setThreshold(double threshold) {
    threshold_ = threshold;
    select_->use();
    glUniform1f(stopPowerUniform_, float(threshold_ * sourcePower_));
  }

  // Power, then selection of `shooters` patches with k x k hemicubes each (0 shooters: only the
  // total, for the final state).
  void choose(int shooters, int side, bool emittersOnly) {
    timeline_.mark("shoot: choose");
    buf_.bind();
    power_->use();
    glDispatchCompute(groups(sys_.patchCount(), kPowerGroup), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    select_->use();
    glUniform1ui(selectBatch_, GLuint(shooters));
    glUniform1ui(selectSide_, GLuint(side));
    glUniform1i(selectEmitters_, emittersOnly);
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
  void shoot(int shooters, int side, bool emittersOnly) {
    choose(shooters, side, emittersOnly);
    timeline_.mark("shoot: hemicubes");
    hemicubes_->render(0, shooters * side * side);  // centres from the shooter buffer choose() bound
    timeline_.mark("shoot: reconstruct");
    hemicubes_->bindTextures();
    reconstruct_->use();
    glUniform1ui(reconstructSamples_, GLuint(side * side));
    glDispatchCompute(groups(sys_.elementCount(), kReconstructGroup), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
  GpuSolverState readState() {
    GpuSolverState s{};
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(buf_.state, 0, sizeof s, &s);
    return s;
  }

  const RadiositySystem& sys_;
  // Read once: stats() may be asked while another session's context is current (luxel animate
  // --error solves each frame's reference in its own).
  const std::string device_;
  const GlProgressiveSettings o_;
  Buffers buf_;
  std::unique_ptr<LayeredHemicubes> hemicubes_;
  std::unique_ptr<ShaderProgram> power_, select_, reconstruct_;
  GLint selectBatch_ = -1, selectSide_ = -1, selectEmitters_ = -1, reconstructSamples_ = -1;
  GLint stopPowerUniform_ = -1, reconstructRedistributing_ = -1;
  GLint reconstructCrossProjecting_ = -1, reconstructCrossSign_ = -1;
  std::unique_ptr<CrossRedistribution> cross_;  // crossRedistribution only
  bool crossMoved_ = false, openMoverWarned_ = false;
  std::vector<std::string> warnings_;
  std::unique_ptr<ShaderProgram> amounts_, redistribute_, rebase_;  // followChanges only
  float offset_ = 0.0f;
  int redistributionBatch_ = 0;
  double threshold_ = o_.unshotThreshold;
  size_t listCapacity_ = 0;
  std::vector<Rgb> analyticUsed_, emissionUsed_, patchEmissionUsed_;
  uint64_t redistributions_ = 0;
  double secondsRedistributing_ = 0.0;
  int samples_ = 0, batch_ = 0, emitterSide_ = 0, emitterSamples_ = 0, emitterBatch_ = 0;
  size_t emitters_ = 0;
  bool emittersApart_ = false, emittersShot_ = false, done_ = false;
  int shCount_ = 0;  // every shot so far added this many SH coefficients an element to buf_.elementSh
  double sourcePower_ = 0.0, unshotFraction_ = 1.0;
  ProgressThrottle throttle_;
  GpuTimeline timeline_;
  double setupSeconds_ = 0.0, seconds_ = 0.0;
  uint64_t shots_ = 0;
  uint32_t emitterShots_ = 0;
};

}  // namespace

std::unique_ptr<Solver> makeGlProgressiveSolver(const RadiositySystem& system, Context& context,
                                                const GlProgressiveSettings& settings,
                                                std::vector<uint32_t> objectOfPatch) {
  if (settings.samplesPerSide < 1 || settings.samplesPerSide > 8) throw Error("hemicubes per shooter side must be in 1..8");
  if (settings.emitterSamplesPerSide < 0 || settings.emitterSamplesPerSide > 8)
    throw Error("hemicubes per emitter side must be in 1..8 (or 0: as other shooters)");
  if (settings.shootersPerPass < 1 || settings.shootersPerPass > kMaxShootersPerPass)
    throw Error(fmt::format("shooters per pass must be in 1..{}", kMaxShootersPerPass));
  if (settings.passesPerCheck < 1) throw Error("passes per check must be >= 1");
  if (settings.crossRedistribution && !settings.followChanges)
    throw Error("cross-redistribution follows changes: followChanges must be set with it");
  if (settings.crossRedistribution && objectOfPatch.size() != system.patchCount())
    throw Error("cross-redistribution needs each patch's object");
  return std::make_unique<GlProgressiveSolver>(system, context, settings, std::move(objectOfPatch));
}

}  // namespace luxel::gl

// The viewer's GLSL, kept in one place so that `--shaders DIR` can replace any of it from files and
// `shaders.reload` can compile it again while the viewer runs (003's run-time shader reloading).
#include "view_shaders.h"

#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "luxel/error.h"

namespace luxel::viewer {
namespace {

// The scene pass. Radiance is what `luxel render` computes per pixel:
//   L = Le + rho / pi * (H_field + sum of the per-pixel lights' irradiance times visibility),
// with H_field interpolated over the element from its four corner values exactly as the ray
// caster does (bilinear in the quad's (u, v), which Embree and this split into triangles
// (0,1,3) and (2,3,1) give alike; barycentric on triangles).
const char* kSceneVertex = R"(#version 450 core
const int kFinal = 0, kIndirect = 1, kDirect = 2, kRadiosity = 3;
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;
layout(location = 3) in vec2 aCorner;
layout(location = 4) in uint aElement;
layout(location = 5) in uint aFlags;
layout(location = 6) in vec3 aSmoothNormal;
// Per element corner (4 per element): the interpolated field (everything but the per-pixel
// lights), its direct part, and the per-pixel lights' own part (for the radiosity view).
struct Corner { vec4 field; vec4 direct; vec4 perPixel; };
layout(std430, binding = 0) readonly buffer Corners { Corner corners[]; };
uniform mat4 uViewProjection;
// The same depth in every pass (the shadow-volume path draws the scene again for each light).
invariant gl_Position;
out vec3 vPosition;
out vec2 vUv;
out vec2 vCorner;
flat out vec3 vNormal;
flat out uint vElement;
flat out uint vFlags;
// The element's four corner values of what this view shows, read once per vertex rather than once
// per pixel (the fragment shader only blends them).
flat out vec3 vC0, vC1, vC2, vC3;
uniform vec3 uEye;
uniform float uShininess;
#pragma luxel include lights.glsl
#if HIGHLIGHT
out vec3 vSmoothNormal;  // only for highlights: every varying costs llvmpipe per pixel
#endif
#if PER_VERTEX
out vec3 vDiffuse;    // the lights shaded here (only then: every varying costs llvmpipe per pixel)
out vec3 vHighlight;
#endif
vec3 shown(uint i) {
  Corner c = corners[i];
  if (VIEW == kIndirect) return max(c.field.rgb - c.direct.rgb, vec3(0.0));
  if (VIEW == kDirect) return c.direct.rgb;
  if (VIEW == kRadiosity) return c.field.rgb + c.perPixel.rgb;
  return c.field.rgb;
}
void main() {
  vPosition = aPosition;
  vUv = aUv;
  vCorner = aCorner;
  vNormal = aNormal;
  vElement = aElement;
  vFlags = aFlags;
  uint base = aElement * 4u;
  vC0 = shown(base); vC1 = shown(base + 1u); vC2 = shown(base + 2u); vC3 = shown(base + 3u);
#if HIGHLIGHT
  vSmoothNormal = aSmoothNormal;
#endif
#if PER_VERTEX
  vDiffuse = vec3(0.0);
  vHighlight = vec3(0.0);
  if (VIEW == kFinal || VIEW == kDirect)
    shadeLights(aPosition, normalize(aNormal), normalize(aSmoothNormal), normalize(uEye - aPosition), uShininess, vDiffuse, vHighlight);
#endif
  gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
)";

// The per-pixel lights (point, spot, sun), shared by scene.vert (per-vertex shading) and
// scene.frag: uniforms, shadow maps, and the light a surface point gets from each.
const char* kLights = R"(
const int kMaxLights = 8;
layout(binding = 2) uniform samplerCubeArrayShadow uCubeShadows;
layout(binding = 3) uniform sampler2DArrayShadow uSunShadows;
// How many per-pixel lights, compiled in too (LIGHTS) for the same reason as the view.
const int kLightCount = LIGHTS;
uniform vec4 uLightPosition[kMaxLights];   // xyz: position (point, spot) or the way light travels (sun); w: type 0 point, 1 spot, 2 sun
uniform vec4 uLightPower[kMaxLights];      // rgb: colour times intensity; w: shadow slot, -1 none
uniform vec4 uLightSpot[kMaxLights];       // xyz: spot axis (unit); z..: w = cos outer
uniform float uLightCosInner[kMaxLights];
uniform float uShadowFar[kMaxLights];      // cube maps: the distance depth 1 stands for
uniform float uShadowTexel[kMaxLights];    // tan of half a texel's angle (cube) or a texel's size (sun)
uniform mat4 uSunMatrix[kMaxLights];       // world to the sun map's [0,1]^3

// Irradiance from light i at this point, shadowed by its map: the same formulas as the solver's
// sampleLight (transport/light_sampling.cpp), front side only.
vec3 lightIrradiance(int i, vec3 p, vec3 n) {
  int type = int(uLightPosition[i].w);
  vec3 power = uLightPower[i].rgb;
  int slot = int(uLightPower[i].w);
  if (type == 2) {
    vec3 w = -uLightPosition[i].xyz;
    float c = max(dot(n, w), 0.0);
    if (c <= 0.0) return vec3(0.0);
    float visible = 1.0;
    if (slot >= 0) {
      // Offset along the normal by a few texels: no acne on lit faces, little peter-panning.
      vec3 q = p + n * (2.0 * uShadowTexel[i]);
      vec4 s = uSunMatrix[i] * vec4(q, 1.0);
      visible = texture(uSunShadows, vec4(s.xy, float(slot), s.z));
    }
    return power * c * visible;
  }
  vec3 d = uLightPosition[i].xyz - p;
  float r2 = dot(d, d);
  if (r2 <= 0.0) return vec3(0.0);
  float r = sqrt(r2);
  vec3 w = d / r;
  float c = max(dot(n, w), 0.0);
  if (c <= 0.0) return vec3(0.0);
  float falloff = 1.0;
  if (type == 1) {
    float cosOuter = uLightSpot[i].w, cosInner = uLightCosInner[i];
    float t = clamp((dot(-w, uLightSpot[i].xyz) - cosOuter) / max(cosInner - cosOuter, 1e-6), 0.0, 1.0);
    falloff = t * t;
    if (falloff <= 0.0) return vec3(0.0);
  }
  float visible = 1.0;
  if (slot >= 0) {
    vec3 q = p + n * (2.0 * uShadowTexel[i] * r);  // a texel grows with the distance from the light
    vec3 from = q - uLightPosition[i].xyz;
    visible = texture(uCubeShadows, vec4(from, float(slot)), length(from) / uShadowFar[i]);
  }
  return power * (falloff * c / r2) * visible;
}

// The per-pixel lights' irradiance at p with the element's normal n (diffuse), and the same weighted
// by the Blinn-Phong lobe pow(S.H, shininess) about the smooth normal s (Material::specular's
// convention: radiance = specular / pi * that): a curved mesh's highlight does not show its facets.
void shadeLights(vec3 p, vec3 n, vec3 s, vec3 toEye, float shininess, out vec3 diffuse, out vec3 highlight) {
  diffuse = vec3(0.0);
  highlight = vec3(0.0);
  for (int i = 0; i < kLightCount; ++i) {
    vec3 e = lightIrradiance(i, p, n);
    diffuse += e;
    if (HIGHLIGHT != 0 && e != vec3(0.0)) {
      vec3 toLight = uLightPosition[i].w == 2.0 ? -uLightPosition[i].xyz : normalize(uLightPosition[i].xyz - p);
      highlight += e * pow(max(dot(s, normalize(toLight + toEye)), 0.0), shininess);
    }
  }
}
)";

const char* kSceneFragment = R"(#version 450 core
const float kInvPi = 0.31830988618;
const uint kHasTwin = 1u, kTriangle = 2u;
// Views (ViewMode).
const int kFinal = 0, kIndirect = 1, kDirect = 2, kRadiosity = 3, kPatches = 4, kElements = 5, kDensity = 6, kUnshot = 7;

in vec3 vPosition;
in vec2 vUv;
in vec2 vCorner;
flat in vec3 vNormal;
flat in uint vElement;
flat in uint vFlags;
flat in vec3 vC0, vC1, vC2, vC3;

layout(std430, binding = 1) readonly buffer Patches { uint patchOf[]; };
layout(std430, binding = 2) readonly buffer Unshot { float unshotHeat[]; };

uniform vec3 uReflectance;
uniform vec3 uEmission;
uniform bool uReflectanceTexture;
uniform bool uEmissionTexture;
layout(binding = 0) uniform sampler2D uReflectanceMap;
layout(binding = 1) uniform sampler2D uEmissionMap;

// The view is compiled in (scene.frag is built once per view with VIEW defined): a rasteriser on
// the CPU runs every branch of a shader whose branches depend on a uniform, and the seven views'
// code cost llvmpipe twice the time of one.
const int kView = VIEW;
uniform vec3 uEye;
uniform float uTexelSize;  // the density view's checker cell, scene units
uniform vec3 uSpecular;     // the material's highlight (Material::specular, shininess)
uniform float uShininess;
#pragma luxel include lights.glsl
// PER_VERTEX: the lights are shaded at the element corners and interpolated (004's per-vertex
// option, Gouraud); else per pixel.
#if HIGHLIGHT
in vec3 vSmoothNormal;
#endif
#if PER_VERTEX
in vec3 vDiffuse;
in vec3 vHighlight;
#endif

// Radiance times uOutputScale (about the exposure, so that a half-float picture holds it: values
// near 0.18, clamped below half float's largest); a = 1 where a surface is seen (auto exposure's
// coverage).
layout(location = 0) out vec4 outRadiance;
uniform float uOutputScale;
void store(vec3 radiance) { outRadiance = vec4(min(radiance * uOutputScale, vec3(60000.0)), 1.0); }
layout(location = 1) out uint outElement;   // element + 1, 0 for the background (picking)

// What the view shows of the solution here: the corner values blended as the ray caster does.
vec3 fieldValue() {
  float u = vCorner.x, v = vCorner.y;
  if ((vFlags & kTriangle) != 0u) return (1.0 - u - v) * vC0 + u * vC1 + v * vC2;
  return (1.0 - u) * (1.0 - v) * vC0 + u * (1.0 - v) * vC1 + u * v * vC2 + (1.0 - u) * v * vC3;
}

vec3 hashColour(uint x) {
  x ^= x >> 16; x *= 0x7feb352du; x ^= x >> 15; x *= 0x846ca68bu; x ^= x >> 16;
  return vec3(float(x & 255u), float((x >> 8) & 255u), float((x >> 16) & 255u)) / 255.0 * 0.8 + 0.2;
}

void main() {
  outElement = vElement + 1u;
  if (!gl_FrontFacing) {
    // The back of a two-sided face is its twin's front, drawn in the same place: let it win.
    if ((vFlags & kHasTwin) != 0u) discard;
    store(vec3(0.0));  // one-sided surfaces send nothing backwards
    return;
  }
  vec3 rho = uReflectance;
  if (uReflectanceTexture) rho *= texture(uReflectanceMap, vUv).rgb;
  vec3 le = uEmission;
  if (uEmissionTexture) le *= texture(uEmissionMap, vUv).rgb;
  vec3 n = normalize(vNormal);

  if (kView == kPatches || kView == kElements) {
    vec3 c = hashColour(kView == kPatches ? patchOf[vElement] : vElement);
    store(c * (0.35 + 0.65 * abs(dot(n, normalize(uEye - vPosition)))));
    return;
  }
  if (kView == kUnshot) {
    // Where the solve has work left: black (none, or a millionth of the most), blue, red, yellow (the most).
    float t = unshotHeat[vElement];
    vec3 c = t <= 0.0 ? vec3(0.0) : mix(mix(vec3(0.05, 0.1, 0.6), vec3(0.9, 0.1, 0.1), clamp(2.0 * t, 0.0, 1.0)),
                                         vec3(1.0, 0.95, 0.2), clamp(2.0 * t - 1.0, 0.0, 1.0));
    store(c * (0.35 + 0.65 * abs(dot(n, normalize(uEye - vPosition)))));
    return;
  }
  if (kView == kDensity) {
    // A checker of lightmap texels at the bake's density, laid on the plane the face mostly faces.
    vec3 a = abs(n);
    vec2 q = a.x > a.y && a.x > a.z ? vPosition.yz : (a.y > a.z ? vPosition.xz : vPosition.xy);
    ivec2 cell = ivec2(floor(q / uTexelSize));
    float shade = ((cell.x + cell.y) & 1) == 0 ? 0.75 : 0.25;
    store(mix(vec3(shade), hashColour(patchOf[vElement]) * shade, 0.3));
    return;
  }

  vec3 perPixel = vec3(0.0), highlight = vec3(0.0);
  if (kView == kFinal || kView == kDirect) {
#if PER_VERTEX
    perPixel = vDiffuse;
    highlight = vHighlight;
#else
#if HIGHLIGHT
    shadeLights(vPosition, n, normalize(vSmoothNormal), normalize(uEye - vPosition), uShininess, perPixel, highlight);
#else
    shadeLights(vPosition, n, n, vec3(0.0), 0.0, perPixel, highlight);
#endif
#endif
  }
  vec3 shine = uSpecular * kInvPi * highlight;  // display only: the solve is diffuse
  if (LIGHT_ONLY != 0) {
    // One light's pass of the shadow-volume path, added where the stencil says it is seen.
    store(rho * kInvPi * perPixel + shine);
    return;
  }
  // Final: the field and the per-pixel lights; indirect: the field less its direct part; direct:
  // the field's direct part and the per-pixel lights; radiosity: every light from the elements.
  vec3 radiance = rho * kInvPi * (fieldValue() + perPixel) + shine;
  if (kView != kIndirect) radiance += le;
  store(radiance);
}
)";

// Stencil shadow volumes (004 section 3.2; z-fail with the far plane at infinity, Everitt and
// Kilgard 2002): each triangle facing away from the light (004's caster set (c)) is extruded away
// from it into a closed volume: itself reversed as the near cap, itself at infinity as the far cap
// (a point light's), and a side for each edge. Every caster's volume is closed on its own, so no
// adjacency is needed and open or non-manifold meshes are fine.
const char* kVolumeVertex = R"(#version 450 core
layout(location = 0) in vec3 aPosition;
out vec3 vPosition;
flat out int vIndex;  // the welded corner's index (gl_VertexID of an indexed draw)
void main() { vPosition = aPosition; vIndex = gl_VertexID; }
)";
// Seed 004's back-facing casters, each with its three neighbours (viewer/shadow_casters.h): the
// caps from the caster itself, a side only along an edge whose neighbour does not also cast.
// Whether a triangle faces the light is computed from its corners in index order, so that a
// triangle and its neighbour's invocation agree to the bit on the edge they share; otherwise
// rounding could leave a side drawn by neither and the volume open.
const char* kVolumeGeometry = R"(#version 450 core
layout(triangles_adjacency) in;
layout(triangle_strip, max_vertices = 18) out;
in vec3 vPosition[];
flat in int vIndex[];
uniform mat4 uViewProjection;
uniform vec4 uLight;  // w = 1: a point light at xyz; w = 0: a sun, light travelling along xyz
vec4 atInfinity(vec3 p) { return uLight.w > 0.5 ? vec4(p - uLight.xyz, 0.0) : vec4(uLight.xyz, 0.0); }
void emit(vec4 p) { gl_Position = uViewProjection * p; EmitVertex(); }
void side(vec3 p, vec3 q) { emit(vec4(p, 1.0)); emit(vec4(q, 1.0)); emit(atInfinity(p)); emit(atInfinity(q)); EndPrimitive(); }
// True when the triangle (vertices i, j, k of the input, in winding order) has its back to the light.
bool casts(int i, int j, int k) {
  // Rotate so that the smallest index comes first: the same winding, the same arithmetic.
  int a = i, b = j, c = k;
  if (vIndex[j] < vIndex[a] && vIndex[j] < vIndex[k]) { a = j; b = k; c = i; }
  else if (vIndex[k] < vIndex[a] && vIndex[k] < vIndex[j]) { a = k; b = i; c = j; }
  vec3 p = vPosition[a];
  vec3 towardsLight = uLight.w > 0.5 ? uLight.xyz - p : -uLight.xyz;
  precise float facing = dot(cross(vPosition[b] - p, vPosition[c] - p), towardsLight);  // no fused, reordered arithmetic
  return facing < 0.0;
}
void main() {
  if (!casts(0, 2, 4)) return;  // lit side towards the light: not a caster
  vec3 a = vPosition[0], b = vPosition[2], c = vPosition[4];
  emit(vec4(a, 1.0)); emit(vec4(c, 1.0)); emit(vec4(b, 1.0)); EndPrimitive();
  if (uLight.w > 0.5) { emit(atInfinity(a)); emit(atInfinity(b)); emit(atInfinity(c)); EndPrimitive(); }
  // The neighbour across a-b is (b, a, n): it shares the edge the other way round. None (n is the
  // caster's own third corner): the side is drawn.
  if (vIndex[1] == vIndex[4] || !casts(2, 0, 1)) side(a, b);
  if (vIndex[3] == vIndex[0] || !casts(4, 2, 3)) side(b, c);
  if (vIndex[5] == vIndex[2] || !casts(0, 4, 5)) side(c, a);
}
)";
const char* kVolumeFragment = R"(#version 450 core
void main() {}
)";

// Depth of a point light's cube map: distance from the light over the far distance, so that one
// comparison serves every face.
const char* kShadowVertex = R"(#version 450 core
layout(location = 0) in vec3 aPosition;
uniform mat4 uViewProjection;
out vec3 vPosition;
void main() { vPosition = aPosition; gl_Position = uViewProjection * vec4(aPosition, 1.0); }
)";
const char* kCubeShadowFragment = R"(#version 450 core
in vec3 vPosition;
uniform vec3 uLight;
uniform float uFar;
void main() { gl_FragDepth = length(vPosition - uLight) / uFar; }
)";
const char* kSunShadowFragment = R"(#version 450 core
void main() {}
)";

// The sky behind the scene, where the scene's sky lights give radiance (skyRadiance in
// transport/light_sampling.cpp): uniform, or the CIE overcast sky's (1 + 2 cos z) / 3 of the zenith.
// Alpha 0: automatic exposure meters on surfaces only, as for `luxel render`'s coverage.
const char* kSkyVertex = R"(#version 450 core
uniform mat4 uInverseViewProjection;
out vec3 vDirection;
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2) * 2.0 - 1.0;
  // Reversed depth with the far plane at infinity: 1 is the near plane, 0.5 twice as far.
  vec4 far = uInverseViewProjection * vec4(p, 0.5, 1.0);
  vec4 near = uInverseViewProjection * vec4(p, 1.0, 1.0);
  vDirection = far.xyz / far.w - near.xyz / near.w;
  gl_Position = vec4(p, 0.0, 1.0);
}
)";
const char* kSkyFragment = R"(#version 450 core
in vec3 vDirection;
uniform vec3 uUp;
uniform vec3 uUniform;   // summed uniform skies' radiance
uniform vec3 uOvercast;  // summed CIE overcast skies' zenith radiance
uniform float uOutputScale;
layout(location = 0) out vec4 outRadiance;
layout(location = 1) out uint outElement;
void main() {
  float c = dot(normalize(vDirection), uUp);
  vec3 l = c > 0.0 ? uUniform + uOvercast * ((1.0 + 2.0 * c) / 3.0) : vec3(0.0);
  outRadiance = vec4(min(l * uOutputScale, vec3(60000.0)), 0.0);
  outElement = 0u;
}
)";

// A glb's baked light as an engine shows it (docs/baking.md): per-vertex radiance as it is;
// per-vertex or lightmap irradiance H (RGBM: rgb * a * range) times base colour over pi, plus
// emission; a transfer lightmap's H relit by the light's SH as the three.js recipe does.
// glTF texture coordinates have v = 0 at the image's top, as the images are stored.
// The texels view (texel_renderer.h): each face at its place in the lightmap atlas, each texel's
// diagnosis fetched whole.
const char* kTexelsVertex = R"(#version 450 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec2 aTexel;  // texel units on its page
layout(location = 2) in float aPage;
layout(location = 3) in uint aElement;  // an element of the face + 1, for picking; 0 for none
uniform mat4 uViewProjection;
out vec2 vTexel;
flat out int vPage;
flat out uint vElement;
void main() {
  vTexel = aTexel;
  vPage = int(aPage);
  vElement = aElement;
  gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
)";
const char* kTexelsFragment = R"(#version 450 core
in vec2 vTexel;
flat in int vPage;
flat in uint vElement;
layout(binding = 0) uniform sampler2DArray uTexels;  // a colour per texel, per page
uniform float uOutputScale;
layout(location = 0) out vec4 outRadiance;
layout(location = 1) out uint outElement;
void main() {
  ivec2 size = textureSize(uTexels, 0).xy;
  ivec2 t = clamp(ivec2(floor(vTexel)), ivec2(0), size - 1);
  outRadiance = vec4(texelFetch(uTexels, ivec3(t, vPage), 0).rgb * uOutputScale, 1.0);
  outElement = vElement;
}
)";
const char* kBakedVertex = R"(#version 450 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec2 aUv0;
layout(location = 2) in vec2 aUv1;
layout(location = 3) in vec3 aColor;
layout(location = 4) in vec3 aNormal;
layout(location = 5) in vec4 aTangent;
layout(location = 6) in vec3 aDirection[8];  // LUXEL_vertex_directional's values
uniform mat4 uViewProjection;
out vec2 vUv0;
out vec2 vUv1;
out vec3 vColor;
out vec3 vNormal;
out vec4 vTangent;
out vec3 vDirection[8];
void main() {
  vUv0 = aUv0;
  vUv1 = aUv1;
  vColor = aColor;
  vNormal = aNormal;
  vTangent = aTangent;
  for (int k = 0; k < 8; ++k) vDirection[k] = aDirection[k];
  gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
)";
const char* kBakedFragment = R"(#version 450 core
const float kInvPi = 0.31830988618;
in vec2 vUv0;
in vec2 vUv1;
in vec3 vColor;
in vec3 vNormal;
in vec4 vTangent;
in vec3 vDirection[8];
uniform int uKind;  // 0 nothing baked, 1 vertex radiance, 2 vertex irradiance, 3 lightmap
// LUXEL_lightmap_directional (docs/baking.md): 0 none, 1 sh-l1, 2 dominant, 3 sh-l2. The lightmap is
// the irradiance at the geometric normal; the directions say how it changes at the normal map's.
uniform int uDirectional;
// The direction values come from the vertices (LUXEL_vertex_directional), not the textures.
uniform bool uVertexDirections;
uniform float uNormalScale;
layout(binding = 2) uniform sampler2D uNormalMap;
layout(binding = 3) uniform sampler2D uDirection[8];
// LUXEL_lightmap_transfer (docs/baking.md): bands (0 for none); the lightmap is T_0 and the ratio
// textures hold q_i = T_i / T_0 as 0.5 + 0.5 q / uRatioScale[i - 1], four numbers a texel (channel
// fastest); uLight is the light's radiance SH. They share units 3.. with uDirection: a material is
// one or the other.
uniform int uTransferBands;
layout(binding = 3) uniform sampler2D uRatio[12];
uniform float uRatioScale[15];
uniform vec3 uLight[16];
uniform vec4 uBaseColor;
uniform bool uBaseTexture;
uniform vec3 uEmission;
uniform float uRgbmRange;
uniform float uOutputScale;
layout(binding = 0) uniform sampler2D uBaseMap;   // sRGB, decoded by the sampler
layout(binding = 1) uniform sampler2D uLightMap;  // RGBM, linear
layout(location = 0) out vec4 outRadiance;
layout(location = 1) out uint outElement;
// One directional light plus a constant (Sloan 2008), in units of the band-0 integral.
float luxelL1(vec3 q, vec3 n) {
  float len = length(q), r = min(len, 1.0);
  return 0.25 * (1.0 - r) + max(dot(n, q), 0.0) * (len > 0.0 ? r / len : 0.0);
}
// Direction texture k's value here, or the vertices' (interpolated as the texels are).
vec3 directionValue(int k) { return uVertexDirections ? vDirection[k] : texture(uDirection[k], vUv1).rgb; }
vec3 directionalFactor(vec3 n, vec3 n0) {
  vec3 f, f0;
  if (uDirectional == 1) {
    vec3 qx = 2.0 * directionValue(0) - 1.0;
    vec3 qy = 2.0 * directionValue(1) - 1.0;
    vec3 qz = 2.0 * directionValue(2) - 1.0;
    for (int c = 0; c < 3; ++c) {
      vec3 q = vec3(qx[c], qy[c], qz[c]);
      f[c] = luxelL1(q, n);
      f0[c] = luxelL1(q, n0);
    }
  } else if (uDirectional == 2) {
    vec3 q = 2.0 * directionValue(0) - 1.0;
    f = vec3(luxelL1(q, n));
    f0 = vec3(luxelL1(q, n0));
  } else {
    vec3 q[9];
    q[0] = vec3(1.0);
    for (int i = 1; i < 9; ++i) q[i] = (2.0 * directionValue(i - 1) - 1.0) * (i < 4 ? 1.7320508 : 2.2360680);
    for (int k = 0; k < 2; ++k) {
      vec3 d = k == 0 ? n : n0;
      vec3 e = 3.1415927 * 0.282095 * q[0] + 2.0943951 * 0.488603 * (q[1] * d.y + q[2] * d.z + q[3] * d.x) +
               0.7853982 * (1.092548 * (q[4] * d.x * d.y + q[5] * d.y * d.z + q[7] * d.x * d.z) +
                            0.315392 * q[6] * (3.0 * d.z * d.z - 1.0) + 0.546274 * q[8] * (d.x * d.x - d.y * d.y));
      if (k == 0) f = e; else f0 = e;
    }
  }
  return vec3(f0.r > 0.0 ? max(f.r, 0.0) / f0.r : 1.0, f0.g > 0.0 ? max(f.g, 0.0) / f0.g : 1.0,
              f0.b > 0.0 ? max(f.b, 0.0) / f0.b : 1.0);
}
// H = T_0 (L_0 + sum_{i>=1} q_i L_i) per channel, clamped at zero (band-limited light rings below
// zero in deep shadow): one dot product of the texel's transfer and the light's SH.
vec3 transferIrradiance(vec3 t0) {
  int n = uTransferBands * uTransferBands;
  float q[48];
  for (int k = 0; k < (3 * (n - 1) + 3) / 4; ++k) {
    vec4 r = texture(uRatio[k], vUv1);
    q[4 * k] = r.r;
    q[4 * k + 1] = r.g;
    q[4 * k + 2] = r.b;
    q[4 * k + 3] = r.a;
  }
  vec3 sum = uLight[0];
  for (int i = 1; i < n; ++i)
    sum += (2.0 * vec3(q[3 * i - 3], q[3 * i - 2], q[3 * i - 1]) - 1.0) * uRatioScale[i - 1] * uLight[i];
  return max(t0 * sum, vec3(0.0));
}
void main() {
  vec3 base = uBaseColor.rgb;
  if (uBaseTexture) base *= texture(uBaseMap, vUv0).rgb;
  vec3 radiance = uEmission;
  // glTF's tangent frame: bitangent = cross(normal, tangent) * w, both along the image's up.
  vec3 n0 = normalize(vNormal), t = normalize(vTangent.xyz), b = cross(n0, t) * vTangent.w;
  vec3 m = 2.0 * texture(uNormalMap, vUv0).rgb - 1.0;
  vec3 n = normalize(t * (m.x * uNormalScale) + b * (m.y * uNormalScale) + n0 * m.z);
  if (uKind == 1) radiance = uDirectional > 0 ? uEmission + (vColor - uEmission) * directionalFactor(n, n0) : vColor;
  else if (uKind == 2) radiance += base * kInvPi * vColor * (uDirectional > 0 ? directionalFactor(n, n0) : vec3(1.0));
  else if (uKind == 3) {
    vec4 rgbm = texture(uLightMap, vUv1);
    vec3 h = rgbm.rgb * rgbm.a * uRgbmRange;
    if (uTransferBands > 0) h = transferIrradiance(h);
    if (uDirectional > 0) h *= directionalFactor(n, n0);
    radiance += base * kInvPi * h;
  }
  outRadiance = vec4(min(radiance * uOutputScale, vec3(60000.0)), 1.0);
  outElement = 0u;
}
)";

// Edges of elements or patches over the picture.
const char* kLineVertex = R"(#version 450 core
layout(location = 0) in vec3 aPosition;
uniform mat4 uViewProjection;
void main() { gl_Position = uViewProjection * vec4(aPosition, 1.0); }
)";
const char* kLineFragment = R"(#version 450 core
uniform vec4 uColour;
layout(location = 0) out vec4 outRadiance;
void main() { outRadiance = uColour; }
)";

// The picture on screen: exposure, tone curve and the sRGB transfer, as src/io/tonemap.cpp does
// for PNG files (the ACES fit of Narkowicz 2016, Reinhard's L/(1+L) on luminance, or a clamp).
const char* kToneVertex = R"(#version 450 core
out vec2 vTexel;
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  vTexel = p;
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";
const char* kToneFragment = R"(#version 450 core
in vec2 vTexel;
layout(binding = 0) uniform sampler2D uRadiance;
uniform float uScale;
uniform int uCurve;  // 0 filmic, 1 reinhard, 2 clamp
out vec4 outColour;
float aces(float x) { return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }
float srgb(float v) { v = clamp(v, 0.0, 1.0); return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055; }
void main() {
  vec3 c = texture(uRadiance, vTexel).rgb;
  c = clamp(c * uScale, vec3(0.0), vec3(1e18));
  if (uCurve == 0) c = vec3(aces(c.r), aces(c.g), aces(c.b));
  else if (uCurve == 1) c = min(c / (1.0 + dot(c, vec3(0.2126, 0.7152, 0.0722))), vec3(1.0));
  else c = min(c, vec3(1.0));
  outColour = vec4(srgb(c.r), srgb(c.g), srgb(c.b), 1.0);
}
)";

}  // namespace

const std::vector<ShaderSource>& builtinShaders() {
  static const std::vector<ShaderSource> shaders = {
      {"scene.vert", kSceneVertex},          {"scene.frag", kSceneFragment},
      {"shadow.vert", kShadowVertex},        {"cube-shadow.frag", kCubeShadowFragment},
      {"sun-shadow.frag", kSunShadowFragment}, {"line.vert", kLineVertex},
      {"line.frag", kLineFragment},          {"sky.vert", kSkyVertex},
      {"sky.frag", kSkyFragment},            {"volume.vert", kVolumeVertex},
      {"volume.geom", kVolumeGeometry},      {"volume.frag", kVolumeFragment},
      {"baked.vert", kBakedVertex},          {"baked.frag", kBakedFragment},
      {"texels.vert", kTexelsVertex},        {"texels.frag", kTexelsFragment},
      {"lights.glsl", kLights},          {"tone.vert", kToneVertex},
      {"tone.frag", kToneFragment},
  };
  return shaders;
}

namespace {

std::string withDefines(std::string source, const std::string& defines) {
  if (defines.empty()) return source;
  const size_t version = source.find("#version");
  const size_t line = version == std::string::npos ? 0 : source.find('\n', version);
  if (line == std::string::npos) return source + "\n" + defines;
  return source.insert(version == std::string::npos ? 0 : line + 1, defines);
}

}  // namespace

// Replaces each `#pragma luxel include NAME` line with shader NAME (from the overrides folder too),
// one level deep: the lights' code is written once for both stages.
std::string withIncludes(const std::string& source, const std::filesystem::path& overrides) {
  static const std::string kInclude = "#pragma luxel include ";
  std::string out;
  size_t at = 0;
  while (true) {
    const size_t found = source.find(kInclude, at);
    if (found == std::string::npos) break;
    const size_t end = source.find('\n', found);
    std::string name = source.substr(found + kInclude.size(), (end == std::string::npos ? source.size() : end) - found - kInclude.size());
    while (!name.empty() && (name.back() == ' ' || name.back() == '\r')) name.pop_back();
    out += source.substr(at, found - at) + shaderFile(name, overrides) + "\n";
    at = end == std::string::npos ? source.size() : end + 1;
  }
  return out + source.substr(at);
}

std::string shaderSource(const std::string& name, const std::filesystem::path& overrides, const std::string& defines) {
  return withDefines(withIncludes(shaderFile(name, overrides), overrides), defines);
}

std::string shaderFile(const std::string& name, const std::filesystem::path& overrides) {
  if (!overrides.empty()) {
    const std::filesystem::path file = overrides / name;
    if (std::filesystem::exists(file)) {
      std::ifstream in(file, std::ios::binary);
      if (!in) throw Error(fmt::format("cannot read the shader '{}'", file.string()));
      std::ostringstream text;
      text << in.rdbuf();
      return text.str();
    }
  }
  for (const ShaderSource& s : builtinShaders())
    if (name == s.name) return s.text;
  throw Error(fmt::format("the viewer has no shader called '{}'", name));
}

}  // namespace luxel::viewer

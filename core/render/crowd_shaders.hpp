#pragma once
// GLSL 4.50 sources of the crowd renderer (internal to core/render).

namespace tourmap::render::shaders {

// Skinned, instanced cluster drawing. Attribute 5 is the per-draw item (instance index, cluster
// fineness 0..255) with divisor 1; the indirect command's baseInstance selects the item range of
// its cluster.
inline constexpr const char* kSceneVertex = R"(#version 450 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 a_color;
layout(location = 3) in uvec4 a_joints;
layout(location = 4) in vec4 a_weights;
layout(location = 5) in uvec2 a_item;

struct Instance {
  vec4 world_row0, world_row1, world_row2;  // model -> world, 3x4
  uint palette_base;                        // first skinning matrix of the instance's pose
  float tint;
  float pad0, pad1;
};
layout(std430, binding = 0) readonly buffer Instances { Instance instances[]; };
layout(binding = 0) uniform samplerBuffer u_palette;  // 3 RGBA32F texels (rows) per matrix

uniform mat4 u_view_proj;
uniform bool u_single_joint;
uniform bool u_heatmap;

out vec3 v_world;
out vec3 v_normal;
out vec3 v_color;

vec3 heat(float t) {  // jet colour map: 0 blue ... 1 red
  return clamp(vec3(1.5) - abs(4.0 * t - vec3(3.0, 2.0, 1.0)), 0.0, 1.0);
}

vec3 hue(float h) {
  vec3 k = clamp(abs(mod(h * 6.0 + vec3(0.0, 4.0, 2.0), 6.0) - 3.0) - 1.0, 0.0, 1.0);
  return mix(vec3(1.0), k, 0.6);
}

void main() {
  Instance inst = instances[a_item.x];
  int base = int(inst.palette_base);
  vec4 r0, r1, r2;
  if (u_single_joint) {
    r0 = texelFetch(u_palette, base * 3);
    r1 = texelFetch(u_palette, base * 3 + 1);
    r2 = texelFetch(u_palette, base * 3 + 2);
  } else {
    // eq. 3.1: v' = sum_j w_j M_j v, blending the matrices' rows.
    r0 = vec4(0.0); r1 = vec4(0.0); r2 = vec4(0.0);
    for (int k = 0; k < 4; ++k) {
      float w = a_weights[k];
      if (w > 0.0) {
        int t = (base + int(a_joints[k])) * 3;
        r0 += w * texelFetch(u_palette, t);
        r1 += w * texelFetch(u_palette, t + 1);
        r2 += w * texelFetch(u_palette, t + 2);
      }
    }
  }
  vec4 p = vec4(a_position, 1.0);
  vec4 posed = vec4(dot(r0, p), dot(r1, p), dot(r2, p), 1.0);
  vec3 n = vec3(dot(r0.xyz, a_normal), dot(r1.xyz, a_normal), dot(r2.xyz, a_normal));
  v_world = vec3(dot(inst.world_row0, posed), dot(inst.world_row1, posed), dot(inst.world_row2, posed));
  v_normal = vec3(dot(inst.world_row0.xyz, n), dot(inst.world_row1.xyz, n), dot(inst.world_row2.xyz, n));
  gl_Position = u_view_proj * vec4(v_world, 1.0);
  if (u_heatmap) {
    v_color = heat(float(a_item.y) / 255.0);
  } else {
    v_color = a_color.rgb;
    if (inst.tint > 0.0) v_color = mix(v_color, hue(inst.tint), 0.5);
  }
}
)";

// One directional light plus ambient; normals turned towards the viewer (models may be
// double-sided or wound either way). Static models (architecture) are shaded flat, from the
// triangle's own plane: their welded vertex normals smear light across sharp edges.
inline constexpr const char* kSceneFragment = R"(#version 450 core
in vec3 v_world;
in vec3 v_normal;
in vec3 v_color;
uniform vec3 u_eye;
uniform vec3 u_light_dir;
uniform bool u_flat;
layout(location = 0) out vec4 o_color;
void main() {
  vec3 face = cross(dFdx(v_world), dFdy(v_world));
  vec3 normal = u_flat ? face : v_normal;
  float len = length(normal);
  vec3 n = len > 0.0 ? normal / len : vec3(0.0, 1.0, 0.0);
  if (dot(n, u_eye - v_world) < 0.0) n = -n;
  float diffuse = max(dot(n, u_light_dir), 0.0);
  o_color = vec4(v_color * (0.4 + 0.6 * diffuse), 1.0);
}
)";

// Full-screen triangle: sky gradient, and the ground plane y = 0 (with its depth, so it hides
// what is below it and serves as an occluder).
inline constexpr const char* kBackgroundVertex = R"(#version 450 core
out vec2 v_ndc;
void main() {
  vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);
  v_ndc = p;
  gl_Position = vec4(p, 0.0, 1.0);
}
)";

inline constexpr const char* kBackgroundFragment = R"(#version 450 core
in vec2 v_ndc;
uniform mat4 u_view_proj;
uniform mat4 u_inv_view_proj;
layout(location = 0) out vec4 o_color;
void main() {
  vec4 a = u_inv_view_proj * vec4(v_ndc, -1.0, 1.0);
  vec4 b = u_inv_view_proj * vec4(v_ndc, 1.0, 1.0);
  vec3 near_p = a.xyz / a.w, far_p = b.xyz / b.w;
  vec3 dir = far_p - near_p;
  float t = abs(dir.y) > 1e-9 ? -near_p.y / dir.y : -1.0;
  if (t >= 0.0 && t <= 1.0) {
    vec3 hit = near_p + t * dir;
    vec2 cell = floor(hit.xz / 2.0);
    float checker = mod(cell.x + cell.y, 2.0);
    float fade = clamp(t * 4.0, 0.0, 1.0);  // checkers fade out towards the far plane
    o_color = vec4(mix(vec3(0.42, 0.45, 0.40) + 0.04 * checker, vec3(0.55, 0.62, 0.68), fade * fade), 1.0);
    vec4 clip = u_view_proj * vec4(hit, 1.0);
    gl_FragDepth = clamp(clip.z / clip.w * 0.5 + 0.5, 0.0, 1.0);
  } else {
    float up = clamp(normalize(dir).y, 0.0, 1.0);
    o_color = vec4(mix(vec3(0.70, 0.80, 0.90), vec3(0.35, 0.55, 0.85), up), 1.0);
    gl_FragDepth = 1.0;
  }
}
)";

// Occlusion tests (sec. 3.5.2, step 2): each box is one instance of a unit cube [-1, 1]^3 with
// its matrix as a per-instance attribute; all boxes go in one draw. With early fragment tests
// only fragments passing the depth test run the shader, which marks the box visible: the same
// answer as one GL_ANY_SAMPLES_PASSED query per box, without a query per box (see test_boxes).
inline constexpr const char* kBoxVertex = R"(#version 450 core
layout(location = 0) in vec3 a_corner;
layout(location = 1) in mat4 a_box_to_clip;
flat out uint v_box;
void main() {
  v_box = uint(gl_InstanceID);
  gl_Position = a_box_to_clip * vec4(a_corner, 1.0);
}
)";

inline constexpr const char* kBoxFragment = R"(#version 450 core
layout(early_fragment_tests) in;
flat in uint v_box;
layout(std430, binding = 1) writeonly buffer Visibility { uint visible[]; };
void main() { visible[v_box] = 1u; }
)";

}  // namespace tourmap::render::shaders

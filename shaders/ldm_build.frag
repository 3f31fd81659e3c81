// Layered depth maps, the build (node/gi/ldm/ldm_gl.h): every fragment of map u_ldm_map inserts
// its depth along the map, t = (p - c).d + R, into its texel's sorted list of the
// u_ldm_layers smallest (ldm_map.h) by an atomic minimum down the list that carries the
// larger value on: the lists end the same whatever order the fragments come in
// (common/gi/ldm/ldm_cpu.c does the same insertion). A depth pushed out of a full list is
// counted. No colour, no depth test: the framebuffer has no attachments.
in vec3 v_position;

layout(std430, binding = 0) buffer ldm_depth_buffer { uint ldm_depth[]; };
layout(std430, binding = 1) readonly buffer ldm_map_buffer { vec4 ldm_map[]; };
layout(std430, binding = 2) buffer ldm_overflow_buffer { uint ldm_overflow; };

uniform int u_ldm_map;
uniform int u_ldm_resolution;
uniform int u_ldm_layers;
uniform vec3 u_ldm_centre;
uniform float u_ldm_radius;

const uint LDM_EMPTY = 0xffffffffu;

void main()
{
    vec3 d = ldm_map[3 * u_ldm_map + 2].xyz;
    float t = max(dot(v_position - u_ldm_centre, d) + u_ldm_radius, 0.0);
    uint z = floatBitsToUint(t);
    ivec2 px = ivec2(gl_FragCoord.xy);
    uint base = ((uint(u_ldm_map) * uint(u_ldm_resolution) + uint(px.y)) *
                 uint(u_ldm_resolution) + uint(px.x)) * uint(u_ldm_layers);
    for (int i = 0; i < u_ldm_layers && z != LDM_EMPTY; i++)
        z = max(atomicMin(ldm_depth[base + uint(i)], z), z);
    if (z != LDM_EMPTY)
        atomicAdd(ldm_overflow, 1u);
}

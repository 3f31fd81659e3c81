// Layered depth maps, the trace (node/gi/ldm/ldm_gl.h binds the buffers and uniforms): from a
// point along +d or -d of one map, the distance to the first surface of its texel's
// sorted list (common/gi/ldm/ldm_map.h says where the maps lie; ldm_list_trace() in
// common/gi/ldm/ldm_cpu.c is the same search on the CPU).
layout(std430, binding = 0) readonly buffer ldm_depth_buffer { uint ldm_depth[]; };
layout(std430, binding = 1) readonly buffer ldm_map_buffer { vec4 ldm_map[]; };

uniform int u_ldm_count;        // maps
uniform int u_ldm_resolution;
uniform int u_ldm_layers;
uniform vec3 u_ldm_centre;
uniform float u_ldm_radius;

const uint LDM_EMPTY = 0xffffffffu;

vec3 ldm_direction(int m) { return ldm_map[3 * m + 2].xyz; }

// A texel's side, metres.
float ldm_texel() { return 2.0 * u_ldm_radius / float(u_ldm_resolution); }

// From p along sign * d of map m: the distance to the first surface farther than skip,
// or -1 when there is none (or p lies outside the map).
float ldm_trace(int m, float sign, vec3 p, float skip)
{
    vec3 q = p - u_ldm_centre;
    vec2 uv = (vec2(dot(q, ldm_map[3 * m].xyz), dot(q, ldm_map[3 * m + 1].xyz)) /
               u_ldm_radius + 1.0) * 0.5 * float(u_ldm_resolution);
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(u_ldm_resolution))))
        return -1.0;
    float t = dot(q, ldm_map[3 * m + 2].xyz) + u_ldm_radius;
    ivec2 px = ivec2(uv);
    int base = ((m * u_ldm_resolution + px.y) * u_ldm_resolution + px.x) * u_ldm_layers;
    float best = -1.0;
    for (int i = 0; i < u_ldm_layers; i++) {
        uint z = ldm_depth[base + i];
        if (z == LDM_EMPTY)
            break;
        float along = (uintBitsToFloat(z) - t) * sign;
        if (along > skip) {
            if (sign > 0.0)
                return along; // sorted: the first one beyond is the nearest
            best = best < 0.0 ? along : min(best, along);
        }
    }
    return best;
}

// A surface point p with unit normal n (on the side a trace along +-d leaves it, |n . d| =
// cos_nd) moved along n by half a texel's diagonal times sin(theta): the largest distance
// along n of its own plane over its texel, so the plane lies behind the moved point
// wherever the texel's centre is, and nothing in front of it need be skipped (a wall a
// texel away is still found).
vec3 ldm_lift(vec3 p, vec3 n, float cos_nd)
{
    return p + n * (ldm_texel() * (0.70711 * sqrt(max(1.0 - cos_nd * cos_nd, 0.0)) + 0.01));
}

// From a surface point p with unit normal n along sign * d of map m: the distance from
// the lifted point (ldm_lift()) to the first other surface, or -1.
float ldm_trace_from(int m, float sign, vec3 p, vec3 n)
{
    float c = dot(n, ldm_direction(m)) * sign;
    return ldm_trace(m, sign, ldm_lift(p, c >= 0.0 ? n : -n, abs(c)), 0.01 * ldm_texel());
}


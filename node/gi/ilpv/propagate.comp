// One LPV propagation step on the GPU (lpv_propagate.h; the rule is lpv_transfer.h's):
// each cell gathers what it and its 26 neighbours send it, colours R, G, B together, and
// adds the result into the accumulation images when asked to (the chain's sum, ilpv.h).
//
// A source cell's light in one colour is split into two unit directions s+ and s- (half
// the energy each, mean u = F / E), and each half goes to offset o with the product of
// three per-axis weights w(v, -1) = (sigma - v) / 2, w(v, 0) = 1 - sigma,
// w(v, 1) = (sigma + v) / 2, sigma = (1 + v^2) / 2. A transfer whose segment crosses a
// surface is dropped: bit k of a cell's blockers word blocks the segment to neighbour k,
// and the same segment is marked in both cells, so a cell reads its own word.
//
// With LPV_TILES defined (the default on a real GPU), a work group first splits its 4x4x4
// block plus a one-cell border into shared memory, so each cell is split once per group
// instead of 27 times. Without it, every neighbour is fetched and split again; llvmpipe
// runs that variant faster, its barriers being expensive (docs/node.md). The renderer
// replaces the BODY marker with 27 gather() calls with constant offsets.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

uniform sampler3D u_src_r;
uniform sampler3D u_src_g;
uniform sampler3D u_src_b;
uniform usampler3D u_blockers;
layout(rgba32f, binding = 0) uniform writeonly image3D u_dst_r;
layout(rgba32f, binding = 1) uniform writeonly image3D u_dst_g;
layout(rgba32f, binding = 2) uniform writeonly image3D u_dst_b;
layout(rgba32f, binding = 3) uniform image3D u_accum_r;
layout(rgba32f, binding = 4) uniform image3D u_accum_g;
layout(rgba32f, binding = 5) uniform image3D u_accum_b;

uniform ivec3 u_size;
uniform int u_use_accum;
uniform int u_use_blockers;
uniform float u_keep;       // 1 - l_a
uniform float u_keep_flux;  // (1 - l_a)(1 - l_s)
uniform int u_step_odd;     // step & 1: which axis of the basis around d splits
uniform int u_step_axis;    // step % 3: the direction of light without flux

const float LPV_MIN_Q = 1e-6;

// One cell's light in one colour: half = Y0 E / 2 (0 when nothing is sent) and the two
// directions.
struct split {
    float half_e;
    vec3 sp, sm;
};

split split_light(vec4 L)
{
    split s;
    float e = u_keep * (SH_ENERGY * L.x);
    vec3 f = u_keep_flux * (vec3(-L.w, -L.y, L.z) * (1.0 / SH_Y1));
    float len = sqrt(dot(f, f));
    bool valid = e > 0.0 && !isinf(e) && !isinf(len) && !isnan(len);
    bool has_dir = valid && len > LPV_MIN_Q * e;
    vec3 d = has_dir ? f / len : vec3(u_step_axis == 0, u_step_axis == 1, u_step_axis == 2);
    float q = has_dir ? min(len / e, 1.0) : 0.0;
    float sign = d.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (sign + d.z);
    float b = d.x * d.y * a;
    vec3 t = u_step_odd != 0 ? vec3(b, sign + d.y * d.y * a, -d.y)
                             : vec3(1.0 + sign * d.x * d.x * a, sign * b, -sign * d.x);
    float r = sqrt(max(0.0, 1.0 - q * q));
    s.sp = q * d + r * t;
    s.sm = q * d - r * t;
    s.half_e = valid ? 0.5 * SH_Y0 * e : 0.0;
    return s;
}

float axis_weight(float v, int o)
{
    v = clamp(v, -1.0, 1.0);
    float sigma = 0.5 + 0.5 * v * v;
    return o < 0 ? 0.5 * (sigma - v) : o == 0 ? 1.0 - sigma : 0.5 * (sigma + v);
}

// What a split sends to offset o, as SH coefficients.
vec4 sent(split s, ivec3 o)
{
    float a = s.half_e * axis_weight(s.sp.x, o.x) * axis_weight(s.sp.y, o.y) *
              axis_weight(s.sp.z, o.z);
    float b = s.half_e * axis_weight(s.sm.x, o.x) * axis_weight(s.sm.y, o.y) *
              axis_weight(s.sm.z, o.z);
    const float k = SH_Y1 / SH_Y0;
    vec3 dir = a * s.sp + b * s.sm;
    return vec4(a + b, -k * dir.y, k * dir.z, -k * dir.x);
}

#ifdef LPV_TILES
const int TILE = 6;        // 4 cells plus a border on each side
shared float s_half[3][TILE * TILE * TILE];
shared vec3 s_sp[3][TILE * TILE * TILE];
shared vec3 s_sm[3][TILE * TILE * TILE];
#endif

uint g_mask;

// Adds what the cell at here - o sends to this one (k: o's neighbour index, 26 for o = 0).
// here: this cell in lattice (no tiles) or tile (LPV_TILES) coordinates.
void gather(ivec3 here, ivec3 cell, ivec3 o, int k, inout vec4 ar, inout vec4 ag, inout vec4 ab)
{
    ivec3 q = cell - o;
    if (any(lessThan(q, ivec3(0))) || any(greaterThanEqual(q, u_size)))
        return;
    // The segment to q is neighbour 25 - k of this cell.
    if (k < 26 && u_use_blockers != 0 && ((g_mask >> uint(25 - k)) & 1u) != 0u)
        return;
#ifdef LPV_TILES
    int i = (here.x - o.x) + TILE * ((here.y - o.y) + TILE * (here.z - o.z));
    split r, g, b;
    r.half_e = s_half[0][i]; r.sp = s_sp[0][i]; r.sm = s_sm[0][i];
    g.half_e = s_half[1][i]; g.sp = s_sp[1][i]; g.sm = s_sm[1][i];
    b.half_e = s_half[2][i]; b.sp = s_sp[2][i]; b.sm = s_sm[2][i];
#else
    split r = split_light(texelFetch(u_src_r, q, 0));
    split g = split_light(texelFetch(u_src_g, q, 0));
    split b = split_light(texelFetch(u_src_b, q, 0));
#endif
    ar += sent(r, o);
    ag += sent(g, o);
    ab += sent(b, o);
}

void main()
{
    ivec3 cell = ivec3(gl_GlobalInvocationID);
#ifdef LPV_TILES
    ivec3 base = ivec3(gl_WorkGroupID) * 4 - 1;
    for (int i = int(gl_LocalInvocationIndex); i < TILE * TILE * TILE; i += 64) {
        ivec3 c = base + ivec3(i % TILE, (i / TILE) % TILE, i / (TILE * TILE));
        bool inside = all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, u_size));
        ivec3 cc = clamp(c, ivec3(0), u_size - 1);
        split r = split_light(inside ? texelFetch(u_src_r, cc, 0) : vec4(0.0));
        split g = split_light(inside ? texelFetch(u_src_g, cc, 0) : vec4(0.0));
        split b = split_light(inside ? texelFetch(u_src_b, cc, 0) : vec4(0.0));
        s_half[0][i] = r.half_e; s_sp[0][i] = r.sp; s_sm[0][i] = r.sm;
        s_half[1][i] = g.half_e; s_sp[1][i] = g.sp; s_sm[1][i] = g.sm;
        s_half[2][i] = b.half_e; s_sp[2][i] = b.sp; s_sm[2][i] = b.sm;
    }
    barrier();
    ivec3 here = ivec3(gl_LocalInvocationID) + 1;
#else
    ivec3 here = cell;
#endif
    if (any(greaterThanEqual(cell, u_size)))
        return;
    g_mask = u_use_blockers != 0 ? texelFetch(u_blockers, cell, 0).r : 0u;
    vec4 ar = vec4(0.0), ag = vec4(0.0), ab = vec4(0.0);
    // @BODY@
    imageStore(u_dst_r, cell, ar);
    imageStore(u_dst_g, cell, ag);
    imageStore(u_dst_b, cell, ab);
    if (u_use_accum != 0) {
        imageStore(u_accum_r, cell, imageLoad(u_accum_r, cell) + ar);
        imageStore(u_accum_g, cell, imageLoad(u_accum_g, cell) + ag);
        imageStore(u_accum_b, cell, imageLoad(u_accum_b, cell) + ab);
    }
}

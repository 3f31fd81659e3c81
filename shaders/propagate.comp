// One ILPV propagation step on the GPU (lpv_propagate.h): each cell gathers what its 26
// neighbours send it, in the order of lpv_transfer_offsets, colours R, G, B together.
//
// With LPV_TILES defined (the default on a real GPU), a work group first copies its 4x4x4
// block plus a one-cell border of light and blocking into shared memory (cells outside
// the lattice as zeros, which send nothing), so each cell is read from the images once
// per group instead of 27 times. Without it, every neighbour is an image load; llvmpipe
// runs that variant about 5x faster, its barriers being expensive (docs/node.md).
// The renderer replaces the BODY marker with 26 gather() calls whose transfer vectors
// are constants: uniform arrays indexed in a loop are very slow on llvmpipe.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(rgba32f, binding = 0) uniform readonly image3D u_src_r;
layout(rgba32f, binding = 1) uniform readonly image3D u_src_g;
layout(rgba32f, binding = 2) uniform readonly image3D u_src_b;
layout(rgba32f, binding = 3) uniform writeonly image3D u_dst_r;
layout(rgba32f, binding = 4) uniform writeonly image3D u_dst_g;
layout(rgba32f, binding = 5) uniform writeonly image3D u_dst_b;
layout(rgba32f, binding = 6) uniform readonly image3D u_geometry;

uniform ivec3 u_size;
uniform int u_use_blocking;
uniform int u_clamp_negative;
uniform float u_keep;      // 1 - lambda_t
uniform float u_scatter;   // lambda_s

#ifdef LPV_TILES
const int TILE = 6;        // 4 cells plus a border on each side
shared vec4 s_r[TILE * TILE * TILE];
shared vec4 s_g[TILE * TILE * TILE];
shared vec4 s_b[TILE * TILE * TILE];
shared vec4 s_geo[TILE * TILE * TILE];
#define FETCH(image, tile, q) tile[(q).x + TILE * ((q).y + TILE * (q).z)]
#define OUTSIDE(q) false
#else
#define FETCH(image, tile, q) imageLoad(image, q)
#define OUTSIDE(q) (any(lessThan(q, ivec3(0))) || any(greaterThanEqual(q, u_size)))
#endif

// What the neighbour at here - o sends: p = <A|L> with A = (1 - l_t) G + (g_j l_s / G_0, 0,
// 0, 0) (the scattered energy <L|1> g_j l_s as a factor of G, whose energy is <G|1>),
// optionally clamped at 0, times the share 1 - b_j the source cell lets through.
// here: the cell in lattice (images) or tile (LPV_TILES) coordinates.
void gather(ivec3 here, ivec3 o, vec4 g, float outscatter, inout vec4 ar, inout vec4 ag,
            inout vec4 ab)
{
    ivec3 q = here - o;
    if (OUTSIDE(q))
        return;
    vec4 a = u_keep * g;
    a.x += outscatter * u_scatter / g.x;
    vec3 p = vec3(dot(a, FETCH(u_src_r, s_r, q)), dot(a, FETCH(u_src_g, s_g, q)),
                  dot(a, FETCH(u_src_b, s_b, q)));
    if (u_clamp_negative != 0)
        p = max(p, vec3(0.0));
    if (u_use_blocking != 0)
        p *= 1.0 - clamp(dot(FETCH(u_geometry, s_geo, q), g), 0.0, 1.0);
    ar += p.r * g;
    ag += p.g * g;
    ab += p.b * g;
}

void main()
{
#ifdef LPV_TILES
    ivec3 base = ivec3(gl_WorkGroupID) * 4 - 1;
    for (int i = int(gl_LocalInvocationIndex); i < TILE * TILE * TILE; i += 64) {
        ivec3 cell = base + ivec3(i % TILE, (i / TILE) % TILE, i / (TILE * TILE));
        bool inside = all(greaterThanEqual(cell, ivec3(0))) && all(lessThan(cell, u_size));
        s_r[i] = inside ? imageLoad(u_src_r, cell) : vec4(0.0);
        s_g[i] = inside ? imageLoad(u_src_g, cell) : vec4(0.0);
        s_b[i] = inside ? imageLoad(u_src_b, cell) : vec4(0.0);
        s_geo[i] = inside && u_use_blocking != 0 ? imageLoad(u_geometry, cell) : vec4(0.0);
    }
    barrier();
    ivec3 here = ivec3(gl_LocalInvocationID) + 1;
#else
    ivec3 here = ivec3(gl_GlobalInvocationID);
#endif
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(c, u_size)))
        return;
    vec4 ar = vec4(0.0), ag = vec4(0.0), ab = vec4(0.0);
    // @BODY@
    imageStore(u_dst_r, c, ar);
    imageStore(u_dst_g, c, ag);
    imageStore(u_dst_b, c, ab);
}

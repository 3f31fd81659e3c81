// One ILPV propagation step on the GPU (lpv_propagate.h): each cell gathers what its 26
// neighbours send it, in the order of lpv_transfer_offsets, colours R, G, B in parallel.
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

// What neighbour s sends to c: p = <A|L_s> with A = (1 - l_t) G + (g_j l_s / G_0, 0, 0, 0)
// (the scattered energy <L_s|1> g_j l_s as a factor of G, whose energy is <G|1>),
// optionally clamped at 0, times the share 1 - b_j the source cell lets through.
void gather(ivec3 c, ivec3 o, vec4 g, float outscatter, inout vec4 ar, inout vec4 ag,
            inout vec4 ab)
{
    ivec3 s = c - o;
    if (any(lessThan(s, ivec3(0))) || any(greaterThanEqual(s, u_size)))
        return;
    vec4 a = u_keep * g;
    a.x += outscatter * u_scatter / g.x;
    vec3 p = vec3(dot(a, imageLoad(u_src_r, s)), dot(a, imageLoad(u_src_g, s)),
                  dot(a, imageLoad(u_src_b, s)));
    if (u_clamp_negative != 0)
        p = max(p, vec3(0.0));
    if (u_use_blocking != 0)
        p *= 1.0 - clamp(dot(imageLoad(u_geometry, s), g), 0.0, 1.0);
    ar += p.r * g;
    ag += p.g * g;
    ab += p.b * g;
}

void main()
{
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(c, u_size)))
        return;
    vec4 ar = vec4(0.0), ag = vec4(0.0), ab = vec4(0.0);
    // @BODY@
    imageStore(u_dst_r, c, ar);
    imageStore(u_dst_g, c, ag);
    imageStore(u_dst_b, c, ab);
}

// One step of the `paper` transport on the GPU (lpv_paper.h, the thesis's listing 5.3):
// each cell gathers from its 26 neighbours q = cell - o_j, colours R, G, B together,
//   p_j = max(0, (1 - l_a - l_s) <L_q|G_j> + gamma_j l_s <L_q|1>) ,  dst += p_j G_j ,
// dropping a neighbour whose segment to this cell the blockers mark (bit j of q's word is
// bit 25 - j of this cell's: the same segment is marked in both cells). No shared memory,
// local size 4^3, as the thesis's compute shader. The caller replaces the BODY marker with
// lpv_paper_shader_body(): 26 gather() calls with G_j and gamma_j as constants.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

uniform sampler3D u_src_r;
uniform sampler3D u_src_g;
uniform sampler3D u_src_b;
uniform usampler3D u_blockers;
layout(rgba32f, binding = 0) uniform writeonly image3D u_dst_r;
layout(rgba32f, binding = 1) uniform writeonly image3D u_dst_g;
layout(rgba32f, binding = 2) uniform writeonly image3D u_dst_b;

uniform ivec3 u_size;
uniform int u_use_blockers; // 0 in the first step of a frame
uniform float u_keep;       // 1 - l_a - l_s, at least 0
uniform float u_scatter;    // l_s <.|1> per unit of L0: l_s SH_ENERGY

uint g_mask;

void gather(ivec3 cell, ivec3 o, int j, vec4 g, float outscatter, inout vec4 ar,
            inout vec4 ag, inout vec4 ab)
{
    ivec3 q = cell - o;
    if (any(lessThan(q, ivec3(0))) || any(greaterThanEqual(q, u_size)))
        return;
    if (((g_mask >> uint(25 - j)) & 1u) != 0u)
        return;
    vec4 lr = texelFetch(u_src_r, q, 0), lg = texelFetch(u_src_g, q, 0);
    vec4 lb = texelFetch(u_src_b, q, 0);
    vec3 p = u_keep * vec3(dot(lr, g), dot(lg, g), dot(lb, g)) +
             (u_scatter * outscatter) * vec3(lr.x, lg.x, lb.x);
    p = max(p, vec3(0.0));
    ar += p.r * g;
    ag += p.g * g;
    ab += p.b * g;
}

void main()
{
    ivec3 cell = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(cell, u_size)))
        return;
    g_mask = u_use_blockers != 0 ? texelFetch(u_blockers, cell, 0).r : 0u;
    vec4 ar = vec4(0.0), ag = vec4(0.0), ab = vec4(0.0);
    // @BODY@
    imageStore(u_dst_r, cell, ar);
    imageStore(u_dst_g, cell, ag);
    imageStore(u_dst_b, cell, ab);
}

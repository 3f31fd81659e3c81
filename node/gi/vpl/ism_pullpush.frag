// Pull-push hole filling of imperfect shadow maps (node/vpl_ism.c; Marroquim et al. 2007
// as the many-light thesis 3.3.2 describes it), one level per pass over the whole atlas.
// A record is (distance / far, x, y in level-0 texels, radius in level-0 texels): a disk
// of surface; radius 0: empty. Of several records, those within u_interval behind the
// nearest are one front surface (the rest are occluded): they merge at their weighted
// mean depth and position, with the radius that takes in each one's disk.
//   pull (default): a texel of level k + 1 from its four texels of level k (u_fine).
//   push (ISM_PUSH): a texel of level k keeps its pulled record (u_fine); an empty one
//   takes the surface interpolated from the four nearest texels of level k + 1 (u_coarse,
//   already pushed; weights 9 3 3 1, those in the texel's own tile, and only records whose
//   disk covers the texel's centre). Marroquim's push also overwrites a record that lies
//   behind that surface; with a few points per map the merged disks are coarse and that
//   darkened the default room (docs/node.md has the figures), so holes alone are filled.
uniform sampler2D u_fine;
uniform float u_interval;     // depth span of one surface: a point's diameter / far
#ifdef ISM_PUSH
uniform sampler2D u_coarse;
uniform int u_texel;          // level-0 texels per texel of level k
uniform int u_tile;           // texels per tile side at level k + 1
#endif

layout(location = 0) out vec4 out_point;

vec4 ism_merge(vec4 r[4], float w[4])
{
    float front = 2.0;
    for (int k = 0; k < 4; k++)
        if (r[k].w > 0.0 && w[k] > 0.0)
            front = min(front, r[k].x);
    vec3 sum = vec3(0.0);
    float ws = 0.0;
    for (int k = 0; k < 4; k++)
        if (r[k].w > 0.0 && w[k] > 0.0 && r[k].x <= front + u_interval) {
            sum += w[k] * r[k].xyz;
            ws += w[k];
        }
    if (!(ws > 0.0))
        return vec4(0.0);
    vec3 mean = sum / ws;
    float radius = 0.0;
    for (int k = 0; k < 4; k++)
        if (r[k].w > 0.0 && w[k] > 0.0 && r[k].x <= front + u_interval)
            radius = max(radius, distance(r[k].yz, mean.yz) + r[k].w);
    return vec4(mean, radius);
}

void main()
{
    ivec2 f = ivec2(gl_FragCoord.xy);
    vec4 r[4];
    float w[4];
#ifndef ISM_PUSH
    for (int k = 0; k < 4; k++) {
        r[k] = texelFetch(u_fine, 2 * f + ivec2(k & 1, k >> 1), 0);
        w[k] = 1.0;
    }
    out_point = ism_merge(r, w);
#else
    vec4 own = texelFetch(u_fine, f, 0);
    vec2 centre = (vec2(f) + 0.5) * float(u_texel);
    ivec2 parent = f / 2, step = 2 * (f & 1) - 1;
    ivec2 lo = parent / u_tile * u_tile, hi = lo + u_tile - 1;
    const float weight[4] = float[4](9.0, 3.0, 3.0, 1.0);
    for (int k = 0; k < 4; k++) {
        ivec2 c = parent + step * ivec2(k & 1, k >> 1);
        bool inside = all(greaterThanEqual(c, lo)) && all(lessThanEqual(c, hi));
        r[k] = inside ? texelFetch(u_coarse, c, 0) : vec4(0.0);
        w[k] = r[k].w > 0.0 && distance(r[k].yz, centre) <= r[k].w ? weight[k] : 0.0;
    }
    vec4 v = ism_merge(r, w);
    out_point = own.w > 0.0 ? own : v;
#endif
}

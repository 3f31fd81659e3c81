// The vpl method's gather (node/gi/vpl/gi_vpl.h): each VPL's light at a point, tested
// against its shadow map, summed over the VPLs a point's cluster lists. For the method's
// shading snippet (vpl_shade.glsl) and its de-interleaved pass (vpl_deinterleave.frag).
uniform int u_vpl_count;             // 0: no VPL gather
uniform sampler2D u_vpls;            // VPL i: texels (0, i) position + area, (1, i) normal
                                     // + squared influence radius, (2, i) flux, W
uniform sampler2DArrayShadow u_vpl_shadow; // cube faces of every VPL as tiles: distance / far
uniform int u_vpl_face;              // texels per face side
uniform int u_vpl_tiles;             // tiles per atlas side
uniform float u_vpl_far;
uniform vec3 u_vpl_face_axis[6];     // face 2 a + (negative): axis, right, up (gi_vpl.c)
uniform vec3 u_vpl_face_right[6];
uniform vec3 u_vpl_face_up[6];
uniform int u_vpl_clustered;         // 0: every VPL; else the lists of p's cluster
uniform usampler2D u_vpl_cluster_first; // cluster c's list: [entry c, entry c + 1)
uniform usampler2D u_vpl_cluster_index; // VPL indices, ascending per cluster
uniform int u_vpl_list_row;          // entries per texel row of both
uniform vec3 u_vpl_grid_apex;        // the grid (common/gi/vpl/vpl_cluster.h): apex and axes,
uniform vec3 u_vpl_grid_right;
uniform vec3 u_vpl_grid_up;
uniform vec3 u_vpl_grid_forward;
uniform vec4 u_vpl_grid_window;      // window tangents: right min, up min, right max, up max
uniform vec2 u_vpl_grid_depth;       // near, log(far / near)
uniform ivec3 u_vpl_grid_size;       // tiles x, y, slices
uniform int u_vpl_visibility;        // 0: the exact maps above, else imperfect ones (u_ism)
uniform sampler2D u_ism;             // records (distance / far, x, y, radius; radius 0:
                                     // empty), one tile per VPL (vpl_ism.h)
uniform int u_ism_size;              // texels per tile side
uniform int u_ism_tiles;             // tiles per atlas side
uniform float u_ism_radius;          // world radius of the disk each point stands for
uniform float u_vpl_absorption;      // the medium's absorption per metre

// Is VPL i at y visible from p? Its distance map holds, per texel, the distance to the
// nearest surface. p moves along its normal n (which faces the VPL) as in shade.frag's
// shadow():
// a plane at angle beta to the ray changes distance by up to t tan(beta) per texel t =
// 2 z / face (z: depth along the face's axis), the bilinear compare reads texels up to
// sqrt(2) texels away, so o = sqrt(2) t sin(beta) + t / 8 keeps a plane from shadowing
// itself.
float vpl_visible(int i, vec3 y, vec3 p, vec3 n)
{
    vec3 d = p - y;
    vec3 a = abs(d);
    float z = max(a.x, max(a.y, a.z));
    float r = length(d);
    float cos_b = abs(dot(n, d)) / r;
    float sin_b = sqrt(max(1.0 - cos_b * cos_b, 0.0));
    float t = 2.0 * z / float(u_vpl_face);
    d += n * (t * (1.414214 * sin_b + 0.125));
    a = abs(d);
    int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    int face = 2 * axis + (d[axis] < 0.0 ? 1 : 0);
    float depth = dot(d, u_vpl_face_axis[face]);
    vec2 st = vec2(dot(d, u_vpl_face_right[face]), dot(d, u_vpl_face_up[face])) / depth;
    float size = float(u_vpl_face);
    vec2 texel = clamp((st * 0.5 + 0.5) * size, vec2(0.5), vec2(size - 0.5));
    int per_layer = u_vpl_tiles * u_vpl_tiles;
    int tile = i * 6 + face;
    int k = tile % per_layer;
    vec2 uv = (vec2(k % u_vpl_tiles, k / u_vpl_tiles) * size + texel) / (size * float(u_vpl_tiles));
    return texture(u_vpl_shadow, vec4(uv, float(tile / per_layer), length(d) / u_vpl_far));
}

// Is VPL i at y (normal m) visible from p through its imperfect shadow map? p moves along
// n as in vpl_visible(), for a texel of the paraboloid map (t = 2 r (1 + z) / size at
// distance r, cosine z to m) and for the disk of radius u_ism_radius each record spreads
// a point's depth over: o = (sqrt(2) t + radius) sin(beta) + t / 8. Bilinear weights over
// the four texels around the lookup, within the VPL's tile; an empty texel sees nothing.
float ism_visible(int i, vec3 y, vec3 m, vec3 p, vec3 n)
{
    vec3 d = p - y;
    float r = length(d);
    float size = float(u_ism_size);
    float t = 2.0 * r * (1.0 + ism_project(m, d).z) / size;
    float cos_b = abs(dot(n, d)) / r;
    float sin_b = sqrt(max(1.0 - cos_b * cos_b, 0.0));
    d += n * ((1.414214 * t + u_ism_radius) * sin_b + 0.125 * t);
    vec3 q = ism_project(m, d);
    float depth = length(d) / u_vpl_far;
    ivec2 origin = ivec2(i % u_ism_tiles, i / u_ism_tiles) * u_ism_size;
    vec2 f = clamp((q.xy * 0.5 + 0.5) * size, vec2(0.5), vec2(size - 0.5)) - 0.5;
    ivec2 t0 = ivec2(floor(f));
    vec2 w = fract(f);
    float lit = 0.0;
    for (int k = 0; k < 4; k++) {
        ivec2 o = ivec2(k & 1, k >> 1);
        vec4 record = texelFetch(u_ism, origin + min(t0 + o, ivec2(u_ism_size - 1)), 0);
        vec2 wk = mix(1.0 - w, w, vec2(o));
        lit += record.w <= 0.0 || depth <= record.x ? wk.x * wk.y : 0.0;
    }
    return lit;
}

// Irradiance at p (normal n) from VPL i: a disk of its area A seen on its axis,
// flux cos_l cos_x / (A + pi r^2) (eq. 14 of the high-res RSM paper): a point light's
// flux / pi cos_l cos_x / r^2 away from it, bounded near it; nothing beyond its influence
// radius (vpl_cluster.h).
vec3 vpl_light(int i, vec3 p, vec3 n)
{
    vec4 ya = texelFetch(u_vpls, ivec2(0, i), 0);
    vec3 d = ya.xyz - p;
    float r2 = dot(d, d);
    vec4 nl = texelFetch(u_vpls, ivec2(1, i), 0);
    if (r2 <= 0.0 || r2 > nl.w)
        return vec3(0.0);
    vec3 w = d * inversesqrt(r2);
    float cos_x = dot(n, w);
    float cos_l = -dot(nl.xyz, w);
    if (cos_x <= 0.0 || cos_l <= 0.0)
        return vec3(0.0);
    vec3 flux = texelFetch(u_vpls, ivec2(2, i), 0).rgb;
    float g = cos_l * cos_x / (ya.w + PI * r2) * transmittance(u_vpl_absorption, sqrt(r2));
    float visible = u_vpl_visibility == 0 ? vpl_visible(i, ya.xyz, p, n)
                                          : ism_visible(i, ya.xyz, nl.xyz, p, n);
    return flux * (g * visible);
}

// The cluster holding p: vpl_grid_cluster() of common/gi/vpl/vpl_cluster.c, the same rule.
int vpl_cluster(vec3 p)
{
    vec3 rel = p - u_vpl_grid_apex;
    float depth = dot(rel, u_vpl_grid_forward);
    vec2 t = vec2(dot(rel, u_vpl_grid_right), dot(rel, u_vpl_grid_up)) / depth;
    vec2 f = (t - u_vpl_grid_window.xy) / (u_vpl_grid_window.zw - u_vpl_grid_window.xy);
    float s = log(depth / u_vpl_grid_depth.x) / u_vpl_grid_depth.y;
    ivec3 c = clamp(ivec3(floor(vec3(f, s) * vec3(u_vpl_grid_size))), ivec3(0),
                    u_vpl_grid_size - 1);
    return (c.z * u_vpl_grid_size.y + c.y) * u_vpl_grid_size.x + c.x;
}

uint vpl_list_entry(usampler2D list, int k)
{
    return texelFetch(list, ivec2(k % u_vpl_list_row, k / u_vpl_list_row), 0).r;
}

// Irradiance at p from VPLs first, first + step, ... (an interleaved subset; 0, 1: all)
// among its cluster's, or among every VPL: the same terms in the same order (a cluster
// lists every VPL that can reach it, ascending).
vec3 vpl_irradiance(vec3 p, vec3 n, int first, int step)
{
    vec3 e = vec3(0.0);
    if (u_vpl_clustered == 0) {
        for (int i = first; i < u_vpl_count; i += step)
            e += vpl_light(i, p, n);
        return e;
    }
    int c = vpl_cluster(p);
    int last = int(vpl_list_entry(u_vpl_cluster_first, c + 1));
    for (int k = int(vpl_list_entry(u_vpl_cluster_first, c)); k < last; k++) {
        int i = int(vpl_list_entry(u_vpl_cluster_index, k));
        if (i % step == first)
            e += vpl_light(i, p, n);
    }
    return e;
}
